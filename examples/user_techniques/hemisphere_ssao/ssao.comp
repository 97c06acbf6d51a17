#version 450
#include "aoreplay.glsl"
#include "common.glsl"
// Normal-oriented hemisphere SSAO: `samples` points in the hemisphere around the view-space
// normal, cosine-distributed, up to `radius` away. A point is occluded when the depth buffer's
// surface at its pixel lies in front of it and rises above the pixel's tangent plane by more than
// the bias, within the radius. The tangent-plane test (rather than depth alone) keeps a flat floor
// unoccluded at grazing angles, where one pixel spans a long stretch of depth.

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(vec2(pixel), frame.size))) return;
  float dist = texelFetch(in_linear_depth, pixel, 0).r;
  if (dist <= 0.0) {  // sky occludes nothing
    imageStore(out_ao_raw, pixel, vec4(1.0));
    return;
  }
  vec3 p = viewPosition(vec2(pixel), dist);
  vec3 n = normalize(texelFetch(in_view_normals, pixel, 0).xyz);
  vec3 helper = abs(n.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
  vec3 t = normalize(cross(helper, n));
  vec3 b = cross(n, t);
  float rotation = 6.2831853 * pixelNoise(vec2(pixel));
  float bias = params.bias * frame.radius;
  float occlusion = 0.0;
  for (int k = 0; k < params.samples; ++k) {
    float u = (float(k) + 0.5) / float(params.samples);
    float cosTheta = max(sqrt(1.0 - u), 0.15);  // cosine-weighted, kept off the tangent plane
    float sinTheta = sqrt(1.0 - cosTheta * cosTheta);
    float phi = rotation + 2.3999632 * float(k);  // golden angle
    vec3 dir = t * (cos(phi) * sinTheta) + b * (sin(phi) * sinTheta) + n * cosTheta;
    float scale = frame.radius * mix(0.1, 1.0, u * u);
    vec3 s = p + dir * scale;
    vec4 clip = frame.projection * vec4(s, 1.0);
    if (clip.w <= 0.0) continue;
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    if (!(all(greaterThanEqual(uv, vec2(0.0))) && all(lessThan(uv, vec2(1.0))))) continue;  // also NaN
    ivec2 q = ivec2(uv * frame.size);
    float scene = texelFetch(in_linear_depth, q, 0).r;
    if (scene <= 0.0 || scene >= -s.z) continue;  // sky, or the surface lies behind the sample
    vec3 occluder = viewPosition(vec2(q), scene) - p;
    float height = dot(occluder, n);
    float inRange = smoothstep(0.0, 1.0, frame.radius / max(length(occluder), 1e-6));
    occlusion += height > bias ? inRange : 0.0;
  }
  float visibility = clamp(1.0 - params.strength * occlusion / float(params.samples), 0.0, 1.0);
  imageStore(out_ao_raw, pixel, vec4(visibility));
}
