// Rec. 709 luminance of linear RGB: what the film's variance (render_pixel.glsl) measures a
// colour by. Not in the article: machinery of the estimators'
// error. Written in the GLSL/C++ subset: both backends run this file.
#ifndef PT_COLOR_GLSL
#define PT_COLOR_GLSL

float luminance(vec3 c) {
  return dot(c, vec3(0.2126f, 0.7152f, 0.0722f));
}

#endif  // PT_COLOR_GLSL
