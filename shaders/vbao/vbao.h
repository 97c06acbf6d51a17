#ifndef AOR_VBAO_H
#define AOR_VBAO_H
// Visibility-bitmask AO (Therrien, Levesque and Gilet 2023, arXiv 2301.11376; ambient occlusion
// only): the main pass's specialisation ids, the technique's defaults and its core math as
// functions of their inputs, shared by the shader and C++ (tests check the math on the CPU). What
// each step is and where it comes from: replay/techniques/vbao/README.md.
#include "../horizon/horizon.h"
#include "../common/shared_begin.h"

// Specialisation constant ids of the main pass (2, 4 and 6 are the shared blocks').
AOR_CONST int kVbaoSpecSlices = 0;
AOR_CONST int kVbaoSpecSteps = 1;
AOR_CONST int kVbaoSpecSectors = 3;
AOR_CONST int kVbaoSpecCosine = 5;                   // weighting=cosine (else uniform)
AOR_CONST int kVbaoSpecSampleDistributionPower = 7;  // its float bits, as xegtao's
AOR_CONST uint kVbaoMaxSectors = 32u;                // one uint of bits a slice
AOR_CONST float kVbaoPi = 3.14159265358979f;

AOR_CONST float kVbaoDefaultThickness = 0.25f;       // world units (Bevy's constant)
AOR_CONST float kVbaoDefaultFinalValuePower = 1.0f;  // the bitmask's estimate as it is
// The samples are xegtao's: XeGTAO.h's defaults for where they fall.
AOR_CONST float kVbaoDefaultRadiusMultiplier = 1.457f;
AOR_CONST float kVbaoDefaultFalloffRange = 0.615f;
AOR_CONST float kVbaoDefaultSampleDistributionPower = 2.0f;
AOR_CONST float kVbaoDefaultDepthMipSamplingOffset = 3.30f;

// The main pass's push constants: the horizon blocks' constants, then the slab thickness.
struct VbaoConstants {
  HorizonConstants horizon;
  float thickness;
};

// The sectors [floor(lo x N), ceil(hi x N)) of the N sectors over [0, 1] as bits: those an
// occluder spanning [lo, hi] of the hemisphere touches (none when the span is empty).
AOR_FUNC uint vbaoSectorMask(float lo, float hi, uint sectors) {
  float first = clamp(floor(lo * float(sectors)), 0.0f, float(sectors));
  float end = clamp(ceil(hi * float(sectors)), 0.0f, float(sectors));
  if (!(end > first)) return 0u;
  uint count = uint(end - first);
  uint bits = count >= 32u ? 0xffffffffu : ((1u << count) - 1u);
  return bits << uint(first);
}

// The hemisphere fraction of the slice angle `a` (from the view vector, radians, positive towards
// the slice direction): 0 at the projected normal's angle n - pi/2, 1 at n + pi/2.
AOR_FUNC float vbaoHemisphereFraction(float a, float n) { return (a - n) * (1.0f / kVbaoPi) + 0.5f; }

// The integral from the view vector to `a` of cos(x - n) |sin x| over the slice, signed with `a`:
// GTAO's arc integral (XeGTAO's iarc) on either side, so a sector [a0, a1] weighs
// cumulative(a1) - cumulative(a0), and the whole hemisphere weighs what GTAO's unoccluded slice does.
// cosN, sinN: XeGTAO's cosNorm and sin(n).
AOR_FUNC float vbaoCosineCumulative(float a, float n, float cosN, float sinN) {
  float g = (cosN + 2.0f * a * sinN - cos(2.0f * a - n)) * 0.25f;
  return a >= 0.0f ? g : -g;
}

#include "../common/shared_end.h"
#endif
