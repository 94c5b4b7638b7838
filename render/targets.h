// render/targets.h: GPU-side objects (vertex buffers, the shadow map, the multisampled scene
// framebuffer). Handles are plain unsigned ints so that no GL header leaks out of the .cpp files.
// All functions need the owning context to be current.
#pragma once

#include "render/meshes.h"

namespace frontier::render
{

struct GpuMesh
{
    unsigned vao = 0;
    unsigned vbo = 0;
    int count = 0; // vertices
};

// Attribute 0: position, attribute 1: normal.
GpuMesh uploadMesh(const MeshData& data);
void deleteMesh(GpuMesh& mesh);

// A depth texture with hardware comparison (sampler2DShadow, bilinear PCF) and its framebuffer.
struct ShadowTarget
{
    unsigned texture = 0;
    unsigned fbo = 0;
    int size = 0; // texels per side
};
// The size is clamped to 64..GL_MAX_TEXTURE_SIZE. Throws std::runtime_error if incomplete.
ShadowTarget makeShadowTarget(int requestedSize);
void deleteShadowTarget(ShadowTarget& target);

// RGBA8 colour and 24-bit depth renderbuffers, multisampled when samples > 1.
struct SceneTarget
{
    unsigned fbo = 0;
    unsigned color = 0;
    unsigned depth = 0;
    int samples = 1;
};
// Samples are clamped to 1..GL_MAX_SAMPLES. Throws std::runtime_error if incomplete.
SceneTarget makeSceneTarget(int width, int height, int requestedSamples);
void deleteSceneTarget(SceneTarget& target);

} // namespace frontier::render
