// Texture lookup (issue #19; the contract (README.md), "Materials"): a texel of the
// texture table (textures[], texels[]) at a texture coordinate, with the sampler's wrap
// modes and bilinear (or nearest) filtering, sRGB decoded; KHR_texture_transform; a
// triangle's TEXCOORD_0, TEXCOORD_1 and COLOR_0 at a point, and a texture slot's uv there.
// Beyond the article, whose materials are constant. texture.glsl builds the textured material from these, and intersect.glsl's
// alpha mask (alphaMode MASK) reads the base colour's alpha with them; this file needs
// nothing of either, so both can include it.
#ifndef PT_TEXTURE_LOOKUP_GLSL
#define PT_TEXTURE_LOOKUP_GLSL

// The sRGB EOTF (IEC 61966-2-1), exact: an sRGB-encoded value c in [0, 1] as linear.
float srgb_to_linear(float c) {
  if (c <= 0.04045f) return c / 12.92f;
  return pow((c + 0.055f) / 1.055f, 2.4f);
}

// A texture coordinate reduced to one period of its wrap mode (REPEAT: [0, 1], MIRRORED_REPEAT:
// [0, 2], CLAMP_TO_EDGE: [-1, 2]), so that texel indices stay within one period of the
// image. A coordinate that is not finite, or so large that a float has no fraction of a
// texel left, is taken as 0.
float wrap_coordinate(float u, uint mode) {
  if (!(abs(u) <= 1e7f)) u = 0.0f;
  if (mode == kWrapRepeat) return u - floor(u);
  if (mode == kWrapMirroredRepeat) return u - 2.0f * floor(0.5f * u);
  return clamp(u, -1.0f, 2.0f);
}

// A texel index at most one period outside [0, n), as the wrap mode maps it into [0, n).
uint wrap_texel(int i, int n, uint mode) {
  if (mode == kWrapClampToEdge) return uint(clamp(i, 0, n - 1));
  if (mode == kWrapRepeat) {
    if (i < 0) i += n;
    if (i >= n) i -= n;
    return uint(i);
  }
  // MIRRORED_REPEAT: period 2n, its second half the first one reversed.
  if (i < 0) i += 2 * n;
  if (i >= 2 * n) i -= 2 * n;
  return uint(i < n ? i : 2 * n - 1 - i);
}

// Texel (x, y) of texture t, each channel in [0, 1]; sRGB-encoded colour channels are
// decoded to linear when srgb (alpha is always linear).
vec4 texel_at(Texture t, uint x, uint y, bool srgb) {
  uint v = texels[t.offset + y * t.width + x];
  float r = float(v & 255u) / 255.0f;
  float g = float((v >> 8u) & 255u) / 255.0f;
  float b = float((v >> 16u) & 255u) / 255.0f;
  float a = float(v >> 24u) / 255.0f;
  if (srgb) return vec4(srgb_to_linear(r), srgb_to_linear(g), srgb_to_linear(b), a);
  return vec4(r, g, b, a);
}

// a + (b - a) t: exactly a where a == b, so that a constant texture gives its constant.
vec4 lerp4(vec4 a, vec4 b, float t) {
  return a + (b - a) * t;
}

// Texture `index` at uv (glTF: (0, 0) is the image's top-left corner), each texel decoded
// before filtering (sRGB colour is filtered as linear light): bilinear between the 4
// texels around uv (texel centres at half-integers), or the nearest texel
// (kFilterNearest). No mipmaps: a pixel's many samples average the texture over it.
vec4 texture_lookup(uint index, vec2 uv, bool srgb) {
  Texture t = textures[index];
  int w = int(t.width);
  int h = int(t.height);
  float x = wrap_coordinate(uv.x, t.wrap_s) * float(t.width);
  float y = wrap_coordinate(uv.y, t.wrap_t) * float(t.height);
  if (t.mag_filter == kFilterNearest) {
    return texel_at(t, wrap_texel(int(floor(x)), w, t.wrap_s), wrap_texel(int(floor(y)), h, t.wrap_t), srgb);
  }
  float sx = x - 0.5f;
  float sy = y - 0.5f;
  float fx = floor(sx);
  float fy = floor(sy);
  int i0 = int(fx);
  int j0 = int(fy);
  uint x0 = wrap_texel(i0, w, t.wrap_s);
  uint x1 = wrap_texel(i0 + 1, w, t.wrap_s);
  uint y0 = wrap_texel(j0, h, t.wrap_t);
  uint y1 = wrap_texel(j0 + 1, h, t.wrap_t);
  vec4 top = lerp4(texel_at(t, x0, y0, srgb), texel_at(t, x1, y0, srgb), sx - fx);
  vec4 bottom = lerp4(texel_at(t, x0, y1, srgb), texel_at(t, x1, y1, srgb), sx - fx);
  return lerp4(top, bottom, sy - fy);
}

// KHR_texture_transform as the rows of a 2x3 matrix (MaterialTextures): (s, t) =
// (dot(row_s, (u, v, 1)), dot(row_t, (u, v, 1))). The identity gives uv back exactly.
vec2 transform_uv(vec3 row_s, vec3 row_t, vec2 uv) {
  return vec2(row_s.x * uv.x + row_s.y * uv.y + row_s.z, row_t.x * uv.x + row_t.y * uv.y + row_t.z);
}

// TEXCOORD_0, TEXCOORD_1 and COLOR_0 of a triangle at the point of barycentric weights b1
// (p1), b2 (p2), written so that equal corners give their value exactly.
vec2 triangle_uv(TriangleAttributes a, float b1, float b2) {
  vec2 uv0 = vec2(a.uv0);
  return uv0 + (vec2(a.uv1) - uv0) * b1 + (vec2(a.uv2) - uv0) * b2;
}

vec2 triangle_uv_set1(TriangleAttributes a, float b1, float b2) {
  vec2 uv0 = vec2(a.set1_uv0);
  return uv0 + (vec2(a.set1_uv1) - uv0) * b1 + (vec2(a.set1_uv2) - uv0) * b2;
}

// Where texture slot `slot` (kSlot*) of a material reads its texture at the point (b1, b2):
// the slot's texture coordinate set there (bit `slot` of tex_coord_sets: TEXCOORD_1, else
// TEXCOORD_0) through its KHR_texture_transform rows. Every texture lookup goes through it.
vec2 slot_uv(uint tex_coord_sets, uint slot, vec3 row_s, vec3 row_t, TriangleAttributes a, float b1, float b2) {
  vec2 uv = ((tex_coord_sets >> slot) & 1u) != 0u ? triangle_uv_set1(a, b1, b2) : triangle_uv(a, b1, b2);
  return transform_uv(row_s, row_t, uv);
}

vec4 triangle_color(TriangleAttributes a, float b1, float b2) {
  vec4 c0 = vec4(a.color0);
  return c0 + (vec4(a.color1) - c0) * b1 + (vec4(a.color2) - c0) * b2;
}

#endif  // PT_TEXTURE_LOOKUP_GLSL
