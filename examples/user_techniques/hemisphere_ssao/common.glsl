// Shared by ssao.comp and blur.comp (an #include relative to the technique's folder).

// View-space position of the pixel centre `pixel` at linear distance `dist` (> 0) along -Z: the
// point of the pixel's ray through the eye, from the inverse projection.
vec3 viewPosition(vec2 pixel, float dist) {
  vec2 ndc = (2.0 * pixel + 1.0) * frame.inv_size - 1.0;  // row 0 at the top (capture format v1)
  vec4 onRay = frame.inv_projection * vec4(ndc, 0.5, 1.0);
  vec3 p = onRay.xyz / onRay.w;
  return p * (dist / -p.z);
}

// Interleaved gradient noise (Jimenez 2014), shifted per frame so that its pattern moves.
float pixelNoise(vec2 pixel) {
  vec2 shifted = pixel + 5.588238 * float(frame.frame_index % 64u);
  return fract(52.9829189 * fract(dot(shifted, vec2(0.06711056, 0.00583715))));
}
