// Push constants of the mesh pipelines (host/render/mesh_render.c,
// struct mesh_push: the same layout, 128 bytes).
layout(push_constant) uniform MeshPush {
  mat4 mvp;    // world (cm) -> clip
  vec4 key;    // xyz: unit direction toward the key light (world), w: its weight
  vec4 fill;   // the same for the fill light
  vec4 eye;    // w = 1: camera position (perspective); w = 0: unit direction toward the camera (ortho)
  vec4 params; // x: ambient, y: 1 lit (mesh), 0 unlit (grid lines)
} pc;
