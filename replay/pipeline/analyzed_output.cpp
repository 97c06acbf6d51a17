#include "pipeline/analyzed_output.h"

namespace aor {

AnalyzedFrame analyzedFrame(const Capture& capture, const FrameOutput& frame, const std::vector<float>* reference) {
  const auto& desc = capture.frames[size_t(frame.index)];
  return AnalyzedFrame{frame.index,   frame.width, frame.height,       frame.visibility.data(), frame.gbuffer->depth.data(),
                       desc.view,     desc.projection, desc.cut,        frame.historyValid,      frame.resetReason,
                       reference};
}

}  // namespace aor
