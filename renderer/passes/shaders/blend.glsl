// The final images: the lit scene without AO, with the AO term multiplied in, and the AO
// term alone, all sRGB-encoded. Lighting is a fixed directional light plus ambient.
// blend(): one pixel of each, for blend.frag and blend.comp.
uniform sampler2D u_depth;
uniform sampler2D u_normal;
uniform sampler2D u_albedo;
uniform sampler2D u_ao;
uniform bool u_has_ao;

const vec3 kSky = vec3(0.62, 0.72, 0.86);
const vec3 kLight = vec3(0.371391, 0.742781, 0.557086);  // normalised (0.4, 0.8, 0.6)

vec3 to_srgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

void blend(ivec2 p, out vec4 no_ao, out vec4 with_ao, out vec4 ao_only) {
  float ao = u_has_ao ? clamp(texelFetch(u_ao, p, 0).r, 0.0, 1.0) : 1.0;
  if (texelFetch(u_depth, p, 0).r <= 0.0) {
    no_ao = with_ao = vec4(to_srgb(kSky), 1.0);
    ao_only = vec4(1.0);
    return;
  }
  vec3 n = texelFetch(u_normal, p, 0).xyz;
  vec3 albedo = texelFetch(u_albedo, p, 0).rgb;
  vec3 lit = albedo * (0.35 + 0.65 * max(dot(n, kLight), 0.0));
  no_ao = vec4(to_srgb(lit), 1.0);
  with_ao = vec4(to_srgb(lit * ao), 1.0);
  ao_only = vec4(to_srgb(vec3(ao)), 1.0);
}
