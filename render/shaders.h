// render/shaders.h: the GLSL 3.3 programs (a lit pass and a shadow depth pass).
// Handles are plain unsigned/int so that no GL header leaks out of the .cpp files.
#pragma once

namespace frontier::render
{

// Blinn-Phong with one directional light, hemispheric ambient, PCF shadow-map lookups and a
// procedural anti-aliased checker for the floor.
struct LitProgram
{
    unsigned id = 0;
    int model = -1;         // mat4 shape to world (rigid, or floor basis)
    int viewProj = -1;      // mat4
    int lightViewProj = -1; // mat4
    int color = -1;         // vec3 base colour, linear RGB
    int lightDir = -1;      // vec3 direction the light travels (unit)
    int eye = -1;           // vec3 camera position
    int up = -1;            // vec3 world up (for the ambient term)
    int shadowMap = -1;     // sampler2DShadow
    int shadowTexel = -1;   // float, 1 / shadow map size
    int normalOffset = -1;  // float, world units to push lookups off the surface
    int isFloor = -1;       // int, 1 for the checker floor
    int floorOrigin = -1;   // vec3, where the checker's tile corners are anchored
    int floorU = -1;        // vec3, unit, in the plane
    int floorV = -1;        // vec3
    int tile = -1;          // float, checker tile size (m)
    int fadeCentre = -1;    // vec3, centre of the visible floor
    int fade = -1;          // vec2, distances from fadeCentre where the floor fades to the background
    int background = -1;    // vec3 linear background colour
};

struct DepthProgram
{
    unsigned id = 0;
    int mvp = -1; // mat4
};

// Compile and link; throw std::runtime_error with the GL info log on failure.
LitProgram makeLitProgram();
DepthProgram makeDepthProgram();
void deleteProgram(unsigned id);

} // namespace frontier::render
