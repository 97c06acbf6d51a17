#include "run/analyzed_output.h"

#include "metrics/halo_band.h"
#include "technique_api/settings.h"

namespace aor {

AnalyzedFrame analyzedFrame(const Capture& capture, const FrameOutput& frame, const std::vector<float>* reference) {
  const auto& desc = capture.frames[size_t(frame.index)];
  AnalyzedFrame analyzed{frame.index,   frame.width, frame.height,       frame.visibility.data(), frame.gbuffer->depth.data(),
                         desc.view,     desc.projection, desc.cut,        frame.historyValid,      frame.resetReason,
                         reference};
  // The same band for every technique: the capture's radius, never a technique's own setting.
  analyzed.bandRadius = float(captureRadius(capture).value_or(kHaloBandDefaultRadius));
  return analyzed;
}

}  // namespace aor
