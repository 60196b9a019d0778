// Camera rays (the contract (README.md) "Camera"): a perspective pinhole from yfov and the image aspect,
// or an orthographic view of half-extents xmag, ymag; both look down the node's -Z.
// Article: "one ray per pixel sample" of Eq. (2), shot through a jittered point of the pixel.
#ifndef PT_CAMERA_GLSL
#define PT_CAMERA_GLSL

struct Ray {
  vec3 origin;
  vec3 dir;  // unit length
};

// film: position on the image in [0,1)^2, x to the right, y downwards (row 0 on top).
Ray camera_ray(Camera cam, vec2 film) {
  float sx = 2.0f * film.x - 1.0f;
  float sy = 1.0f - 2.0f * film.y;
  vec3 forward = cam.forward;
  vec3 right = vec3(cam.right) * (sx * cam.extent_x);
  vec3 up = vec3(cam.up) * (sy * cam.extent_y);
  // A clip start moves the ray's start to the plane that far along forward (0: the eye).
  if (cam.kind == kCameraOrthographic) {
    return Ray(vec3(cam.origin) + right + up + forward * float(cam.clip_start), forward);
  }
  vec3 dir = normalize(forward + right + up);
  return Ray(vec3(cam.origin) + dir * (float(cam.clip_start) / dot(dir, forward)), dir);
}

#endif  // PT_CAMERA_GLSL
