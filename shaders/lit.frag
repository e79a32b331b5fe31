#version 430 core
// A simple lit surface: one directional light and a sky/ground ambient, enough
// to see the crowd's shapes, its winding and its poses.

in vec3 world_normal;

#ifdef INSTANCED
flat in vec3 instance_colour;  // instanced draws: each instance's own (buffer_skin.vert)
#define base_colour instance_colour
#else
uniform vec3 base_colour;
#endif
uniform vec3 light_direction;  // towards the light, world space, unit length

out vec4 colour;

void main() {
  float length_n = length(world_normal);
  vec3 n = length_n > 0.0 ? world_normal / length_n : vec3(0.0, 1.0, 0.0);
  float diffuse = max(dot(n, light_direction), 0.0);
  float sky = 0.5 + 0.5 * n.y;  // hemisphere ambient: lighter from above
  vec3 lit = base_colour * (0.75 * diffuse + mix(0.12, 0.3, sky));
  colour = vec4(pow(lit, vec3(1.0 / 2.2)), 1.0);  // to sRGB-ish for the PNG
}
