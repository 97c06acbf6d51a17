#version 450
// The shader path's bandwidth (bench/device_rates.cpp): a storage-buffer copy, 16 bytes an
// invocation per step, in a grid-stride loop. A pass reads and writes through the SMs' load/store
// path, not the copy engine a vkCmdCopyBuffer may use (on an H200 that one peaks at 0.85 TB/s,
// below what the blur passes were measured to move), so a pass's byte floor is taken from this.
#extension GL_GOOGLE_include_directive : require
#include "copy_rate.h"

layout(local_size_x = kCopyRateWorkgroupSize) in;
layout(push_constant) uniform Push { CopyRateConstants pc; };
layout(set = 0, binding = 0, std430) readonly buffer Source { vec4 source[]; };
layout(set = 0, binding = 1, std430) writeonly buffer Target { vec4 target[]; };

void main() {
  uint stride = gl_NumWorkGroups.x * kCopyRateWorkgroupSize;
  for (uint i = gl_GlobalInvocationID.x; i < pc.vec4s; i += stride) target[i] = source[i];
}
