#version 450 core
// Each polygon's ID, 1-based so that 0 is the background; the draw's primitive index is the
// polygon's index in the object.
layout(location = 0) out uint o_id;
void main() { o_id = uint(gl_PrimitiveID) + 1u; }
