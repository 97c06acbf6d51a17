// scene.ao_radius becomes the `radius` setting, and loadCapture checks it against the range the
// setting accepts (capture.h: kMinAoRadius, kMaxAoRadius; technique_api/parameters.cpp reads them). The two must agree: the bounds pass
// --set, the doubles just beyond them do not.
#include <cmath>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "capture/capture.h"
#include "techniques/gtao/gtao_settings.h"

namespace aor {
namespace {

TEST(CaptureRadius, TheCapturesRangeIsTheRadiusSettingsRange) {
  Settings settings = gtaoRun();
  EXPECT_NO_THROW(settings.assign(fmt::format("radius={}", kMinAoRadius)));
  EXPECT_NO_THROW(settings.assign(fmt::format("radius={}", kMaxAoRadius)));
  EXPECT_THROW(settings.assign(fmt::format("radius={}", std::nextafter(kMinAoRadius, 0.0))), InputError);
  EXPECT_THROW(settings.assign(fmt::format("radius={}", std::nextafter(kMaxAoRadius, 1e300))), InputError);
}

}  // namespace
}  // namespace aor
