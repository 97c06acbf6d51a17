#version 450
#include "aoreplay.glsl"
#include "common.glsl"
// Normal-oriented hemisphere SSAO: `samples` points in the hemisphere around the view-space
// normal, cosine-distributed, up to `radius` away; a point is occluded when the depth buffer's
// surface at its pixel lies in front of it, by more than the bias and within the radius.

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
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) continue;
    float scene = texture(in_linear_depth, uv).r;
    if (scene <= 0.0) continue;
    float sampleDist = -s.z;
    float inRange = smoothstep(0.0, 1.0, frame.radius / max(abs(dist - scene), 1e-6));
    occlusion += (scene < sampleDist - bias) ? inRange : 0.0;
  }
  float visibility = clamp(1.0 - params.strength * occlusion / float(params.samples), 0.0, 1.0);
  imageStore(out_ao_raw, pixel, vec4(visibility));
}
