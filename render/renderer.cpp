// render/renderer.cpp: the render passes (shadow map, lit MSAA pass, resolve) and the Renderer API.
#define GL_GLEXT_PROTOTYPES 1
#include "render/renderer.h"

#include "render/camera.h"
#include "render/context.h"
#include "render/font.h"
#include "render/meshes.h"
#include "render/scene_bounds.h"
#include "render/shaders.h"
#include "render/targets.h"

#include <GL/osmesa.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

namespace frontier::render
{
namespace
{

using Mat4f = Eigen::Matrix4f;

// Pleasant default colours (sRGB) for moving bodies, by body index.
const core::Vec3 cPalette[] = {
    {0.90, 0.36, 0.27}, // coral
    {0.26, 0.55, 0.85}, // blue
    {0.96, 0.74, 0.20}, // amber
    {0.36, 0.72, 0.42}, // green
    {0.60, 0.42, 0.78}, // purple
    {0.20, 0.70, 0.72}, // teal
    {0.93, 0.52, 0.20}, // orange
    {0.85, 0.45, 0.65}, // pink
};
const core::Vec3 cStaticColor(0.62, 0.62, 0.64);
const core::Vec3 cBackground(0.80, 0.85, 0.90); // sRGB

core::Vec3 toLinear(const core::Vec3& srgb)
{
    core::Vec3 c = srgb.cwiseMax(0.0).cwiseMin(1.0);
    return core::Vec3(std::pow(c.x(), 2.2), std::pow(c.y(), 2.2), std::pow(c.z(), 2.2));
}

// Two unit vectors spanning the plane orthogonal to n; for n = z they are x and y.
void planeBasis(const core::Vec3& n, core::Vec3& u, core::Vec3& v)
{
    const core::Vec3 ref = std::abs(n.x()) < 0.9 ? core::Vec3::UnitX() : core::Vec3::UnitY();
    u = (ref - ref.dot(n) * n).normalized();
    v = n.cross(u);
}

// The "nice" number (1, 2 or 5 times a power of ten) closest to x in log scale.
double niceNumber(double x)
{
    const double power = std::pow(10.0, std::floor(std::log10(x)));
    double best = power;
    for (double m : {1.0, 2.0, 5.0, 10.0})
    {
        if (std::abs(std::log(m * power / x)) < std::abs(std::log(best / x)))
        {
            best = m * power;
        }
    }
    return best;
}

Mat4 poseMatrix(const core::Vec3& position, const core::Quat& rotation)
{
    Mat4 m = Mat4::Identity();
    m.block<3, 3>(0, 0) = rotation.normalized().toRotationMatrix();
    m.block<3, 1>(0, 3) = position;
    return m;
}

void setMatrix(int location, const Mat4& m)
{
    const Mat4f f = m.cast<float>();
    glUniformMatrix4fv(location, 1, GL_FALSE, f.data());
}

void setVec3(int location, const core::Vec3& v)
{
    glUniform3f(location, static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z()));
}

// One shape of one body.
struct DrawItem
{
    std::size_t body = 0;
    Mat4 shapePose = Mat4::Identity(); // shape frame to body frame
    std::size_t mesh = 0;
    core::Vec3 color = core::Vec3::Ones(); // linear RGB
    bool closed = true;                    // generated solids: back faces can be culled
};

struct Floor
{
    core::Vec3 normal = core::Vec3::UnitZ();
    double offset = 0.0;
};

} // namespace

struct Renderer::Impl
{
    core::Model model;
    RenderOptions options;
    Context context;
    core::Vec3 up = core::Vec3::UnitZ();
    core::Vec3 light = -core::Vec3::UnitZ();
    LitProgram lit;
    DepthProgram depth;
    std::vector<GpuMesh> meshes;
    std::vector<DrawItem> items;
    std::vector<Floor> floors;
    GpuMesh quad; // [-1, 1]^2 at z = 0, normal +z
    ShadowTarget shadow;
    SceneTarget scene;

    // Fixed at the first render.
    bool framed = false;
    Mat4 view = Mat4::Identity();
    Mat4 viewProj = Mat4::Identity();
    core::Vec3 eye = core::Vec3::Zero();
    core::Vec3 floorCentre = core::Vec3::Zero();
    double floorHalf = 20.0;
    double tile = 1.0;

    Impl(const core::Model& m, const RenderOptions& o) : model(m), options(o), context(o.width, o.height)
    {
        up = worldUp(model);
        light = defaultLight();
        if (options.lightDirection && options.lightDirection->norm() > 1e-12)
        {
            light = options.lightDirection->normalized();
        }
        lit = makeLitProgram();
        depth = makeDepthProgram();
        buildMeshes();
        shadow = makeShadowTarget(options.shadowMapSize);
        scene = makeSceneTarget(options.width, options.height, options.msaaSamples);
    }

    ~Impl()
    {
        try
        {
            context.makeCurrent();
        }
        catch (...)
        {
            return; // cannot reach the GL objects; they die with the context
        }
        for (GpuMesh& m : meshes)
        {
            deleteMesh(m);
        }
        deleteMesh(quad);
        deleteShadowTarget(shadow);
        deleteSceneTarget(scene);
        deleteProgram(lit.id);
        deleteProgram(depth.id);
    }

    core::Vec3 defaultLight() const
    {
        core::Vec3 a;
        core::Vec3 b;
        planeBasis(up, a, b);
        const double elevation = 55.0 * std::numbers::pi / 180.0;
        const double azimuth = -10.0 * std::numbers::pi / 180.0;
        const core::Vec3 towardsLight =
            std::cos(elevation) * (std::cos(azimuth) * a + std::sin(azimuth) * b) + std::sin(elevation) * up;
        return -towardsLight.normalized();
    }

    void buildMeshes()
    {
        for (std::size_t i = 0; i < model.bodies.size(); ++i)
        {
            const core::Body& body = model.bodies[i];
            core::Vec3 srgb = body.isStatic ? cStaticColor : cPalette[i % std::size(cPalette)];
            if (body.color)
            {
                srgb = *body.color;
            }
            for (const core::Shape& shape : drawnShapes(body))
            {
                if (shape.type == core::ShapeType::Plane)
                {
                    Floor f;
                    f.normal = shape.normal.norm() > 0.0 ? core::Vec3(shape.normal.normalized()) : up;
                    f.offset = shape.offset;
                    floors.push_back(f);
                    continue;
                }
                const MeshData data = shapeMesh(shape);
                if (data.vertexCount() == 0)
                {
                    continue;
                }
                DrawItem item;
                item.body = i;
                item.shapePose = poseMatrix(shape.position_BS, shape.rotation_BS);
                item.mesh = meshes.size();
                item.color = toLinear(srgb);
                item.closed = shape.type != core::ShapeType::Mesh;
                items.push_back(item);
                meshes.push_back(uploadMesh(data));
            }
        }
        MeshData square;
        square.vertices = {-1, -1, 0, 0, 0, 1, 1, -1, 0, 0, 0, 1, 1,  1, 0, 0, 0, 1,
                           -1, -1, 0, 0, 0, 1, 1, 1,  0, 0, 0, 1, -1, 1, 0, 0, 0, 1};
        quad = uploadMesh(square);
    }

    // The points to frame over `states`: the moving bodies' shape corners (all bodies' when none
    // move), with `dropToFloor` each one's drop onto the floors below it too.
    std::vector<core::Vec3> framedPoints(const std::vector<core::State>& states, bool dropToFloor) const
    {
        std::vector<core::Vec3> points;
        for (const core::State& state : states)
        {
            addShapeCorners(model, state, true, points);
        }
        if (points.empty())
        {
            for (const core::State& state : states)
            {
                addShapeCorners(model, state, false, points);
            }
        }
        if (points.empty())
        {
            points = {core::Vec3::Constant(-1.0), core::Vec3::Constant(1.0)};
        }
        if (dropToFloor)
        {
            const std::size_t n = points.size();
            for (std::size_t i = 0; i < n; ++i)
            {
                for (const Floor& f : floors)
                {
                    const double facing = f.normal.dot(up);
                    const double height = f.normal.dot(points[i]) - f.offset;
                    if (facing >= 0.5 && height > 0.0) // not a wall or ceiling, and the point is above
                    {
                        points.push_back(points[i] - (height / facing) * up);
                    }
                }
            }
        }
        return points;
    }

    // The scene's camera, or the automatic one that frames `points`.
    View cameraView(const std::vector<core::Vec3>& points, double aspect) const
    {
        View v;
        if (model.camera.automatic)
        {
            // With a caption, the bodies stay below its band (captionRows() of the image's rows).
            const double topFill = options.caption ? 0.9 - 2.0 * captionRows(options.width, options.height) /
                                                               static_cast<double>(options.height)
                                                   : 0.0;
            v = framePoints(points, up, model.camera.fovDegrees, aspect, 0.9, 0.25, topFill);
        }
        else
        {
            v.eye = model.camera.position;
            v.target = model.camera.lookAt;
            v.up = up;
            v.fovyDegrees = model.camera.fovDegrees;
        }
        return v;
    }

    // Camera and floor placement over `states`: the tightest automatic camera that keeps every pose
    // the moving bodies (all bodies when none move) take in them inside the image. With
    // `dropToFloor` (one state whose future is unknown) each point's drop onto the floors below it
    // is framed too, so that falling bodies stay in view.
    void frame(const std::vector<core::State>& states, bool dropToFloor)
    {
        const double aspect = static_cast<double>(options.width) / options.height;
        const std::vector<core::Vec3> points = framedPoints(states, dropToFloor);
        Bounds framedBox;
        for (const core::Vec3& p : points)
        {
            framedBox.add(p);
        }
        const double radius = std::max(framedBox.radius(), 0.25);
        const View v = cameraView(points, aspect);
        const double fovy = std::clamp(v.fovyDegrees, 1.0, 170.0);
        const double distance = std::max((v.eye - v.target).norm(), 1e-3);
        floorHalf = std::max(20.0, 15.0 * radius + distance);
        tile = niceNumber(std::max(radius, 0.2) / 2.0);
        eye = v.eye;
        view = lookAt(v.eye, v.target, v.up);
        const double zNear = std::max(0.02 * distance, 1e-3);
        const double zFar = distance + 3.0 * floorHalf;
        viewProj = perspective(fovy, aspect, zNear, zFar) * view;
        floorCentre = framedBox.centre();
        framed = true;
    }

    // Light view-projection fitted to all bodies in this state, but not beyond a margin around
    // the moving ones (so that a large static body does not spread the shadow map thin). The fit
    // is quantised (size in steps of 2^(1/4), centre on whole texels) so that shadows of resting
    // bodies do not shimmer while others move.
    Mat4 lightViewProj(const core::State& state, double& texelWorld) const
    {
        Bounds casters = bodyBounds(model, state, false);
        const Bounds moving = bodyBounds(model, state, true);
        if (moving.valid() && casters.valid())
        {
            const double margin = std::max(2.0 * moving.radius(), 1.0);
            casters.lo = casters.lo.cwiseMax(moving.lo - core::Vec3::Constant(margin));
            casters.hi = casters.hi.cwiseMin(moving.hi + core::Vec3::Constant(margin));
        }
        if (!casters.valid())
        {
            casters.add(core::Vec3::Constant(-1.0));
            casters.add(core::Vec3::Constant(1.0));
        }
        const double r = std::pow(2.0, std::ceil(4.0 * std::log2(std::max(casters.radius(), 0.05))) / 4.0);
        texelWorld = 2.0 * r / shadow.size;
        const Mat4 rotation = lookAt(core::Vec3::Zero(), light, up);
        core::Vec3 c = (rotation.block<3, 3>(0, 0) * casters.centre()).eval();
        c.x() = std::round(c.x() / texelWorld) * texelWorld;
        c.y() = std::round(c.y() / texelWorld) * texelWorld;
        c.z() += 2.0 * r; // camera at 2r in front of the centre, looking along the light
        Mat4 viewMatrix = rotation;
        viewMatrix.block<3, 1>(0, 3) = -c;
        return orthographic(-r, r, -r, r, 0.5 * r, 3.5 * r) * viewMatrix;
    }

    Mat4 bodyPose(const core::BodyState& s) const { return poseMatrix(s.position_W, s.orientation_WB); }

    void drawShadowPass(const core::State& state, const Mat4& lightVp)
    {
        glBindFramebuffer(GL_FRAMEBUFFER, shadow.fbo);
        glViewport(0, 0, shadow.size, shadow.size);
        glClear(GL_DEPTH_BUFFER_BIT);
        glDisable(GL_CULL_FACE);
        glEnable(GL_DEPTH_CLAMP); // casters in front of the fitted frustum still cast
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(1.5f, 2.0f);
        glUseProgram(depth.id);
        for (const DrawItem& item : items)
        {
            setMatrix(depth.mvp, lightVp * bodyPose(state.bodies[item.body]) * item.shapePose);
            const GpuMesh& m = meshes[item.mesh];
            glBindVertexArray(m.vao);
            glDrawArrays(GL_TRIANGLES, 0, m.count);
        }
        glDisable(GL_POLYGON_OFFSET_FILL);
        glDisable(GL_DEPTH_CLAMP);
    }

    void drawScenePass(const core::State& state, const Mat4& lightVp, double texelWorld)
    {
        beginScenePass(lightVp, texelWorld);
        drawItems(state);
        drawFloors();
    }

    // The scene's framebuffer cleared, the lit program's view, light and shadow set.
    void beginScenePass(const Mat4& lightVp, double texelWorld)
    {
        glBindFramebuffer(GL_FRAMEBUFFER, scene.fbo);
        glViewport(0, 0, options.width, options.height);
        glClearColor(static_cast<float>(cBackground.x()), static_cast<float>(cBackground.y()),
                     static_cast<float>(cBackground.z()), 1.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glUseProgram(lit.id);
        setMatrix(lit.viewProj, viewProj);
        setMatrix(lit.lightViewProj, lightVp);
        setVec3(lit.lightDir, light);
        setVec3(lit.eye, eye);
        setVec3(lit.up, up);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, shadow.texture);
        glUniform1i(lit.shadowMap, 0);
        glUniform1f(lit.shadowTexel, 1.0f / static_cast<float>(shadow.size));
        glUniform1f(lit.normalOffset, static_cast<float>(1.5 * texelWorld));
        setVec3(lit.background, toLinear(cBackground));
        glUniform1i(lit.isFloor, 0);
    }

    // The bodies' shapes, lit and shadowed.
    void drawItems(const core::State& state)
    {
        for (const DrawItem& item : items)
        {
            if (item.closed)
            {
                glEnable(GL_CULL_FACE);
            }
            else
            {
                glDisable(GL_CULL_FACE);
            }
            setMatrix(lit.model, bodyPose(state.bodies[item.body]) * item.shapePose);
            setVec3(lit.color, item.color);
            const GpuMesh& m = meshes[item.mesh];
            glBindVertexArray(m.vao);
            glDrawArrays(GL_TRIANGLES, 0, m.count);
        }
    }

    // Each floor as a square of half-size floorHalf around the framed centre, tiled and fading out.
    void drawFloors()
    {
        glDisable(GL_CULL_FACE);
        glUniform1i(lit.isFloor, 1);
        glUniform1f(lit.tile, static_cast<float>(tile));
        glUniform2f(lit.fade, static_cast<float>(0.4 * floorHalf), static_cast<float>(floorHalf));
        glBindVertexArray(quad.vao);
        for (const Floor& f : floors)
        {
            core::Vec3 u;
            core::Vec3 v;
            planeBasis(f.normal, u, v);
            const core::Vec3 anchor = f.offset * f.normal; // the world origin dropped onto the plane
            const core::Vec3 centre = floorCentre - (f.normal.dot(floorCentre) - f.offset) * f.normal;
            Mat4 m = Mat4::Identity();
            m.block<3, 1>(0, 0) = floorHalf * u;
            m.block<3, 1>(0, 1) = floorHalf * v;
            m.block<3, 1>(0, 2) = f.normal;
            m.block<3, 1>(0, 3) = centre;
            setMatrix(lit.model, m);
            setVec3(lit.floorOrigin, anchor);
            setVec3(lit.floorU, u);
            setVec3(lit.floorV, v);
            setVec3(lit.fadeCentre, centre);
            glDrawArrays(GL_TRIANGLES, 0, quad.count);
        }
        glBindVertexArray(0);
    }

    void checkSize(const core::State& state) const
    {
        if (state.bodies.size() != model.bodies.size())
        {
            throw std::invalid_argument("render: the state has " + std::to_string(state.bodies.size()) +
                                        " bodies but the model has " + std::to_string(model.bodies.size()));
        }
    }

    void frameOnce(const std::vector<core::State>& states, bool dropToFloor)
    {
        for (const core::State& state : states)
        {
            checkSize(state);
        }
        if (!framed && !states.empty())
        {
            context.makeCurrent();
            frame(states, dropToFloor);
        }
    }

    Image render(const core::State& state)
    {
        checkSize(state);
        context.makeCurrent();
        if (!framed)
        {
            frame({state}, true);
        }
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        double texelWorld = 0.0;
        const Mat4 lightVp = lightViewProj(state, texelWorld);
        drawShadowPass(state, lightVp);
        drawScenePass(state, lightVp, texelWorld);

        // Resolve the samples into the context's own buffer.
        glBindFramebuffer(GL_READ_FRAMEBUFFER, scene.fbo);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        glBlitFramebuffer(0, 0, options.width, options.height, 0, 0, options.width, options.height,
                          GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glFinish();
        if (const GLenum error = glGetError(); error != GL_NO_ERROR)
        {
            char code[16];
            std::snprintf(code, sizeof(code), "0x%04x", error);
            throw std::runtime_error(std::string("render: OpenGL error ") + code);
        }

        Image image;
        image.width = options.width;
        image.height = options.height;
        image.rgba = context.pixels();
        if (options.caption)
        {
            drawCaption(image, captionText(state.time));
        }
        return image;
    }

    std::string captionText(double time) const
    {
        char buffer[64];
        std::snprintf(buffer, sizeof(buffer), "t = %.3f s", time);
        return model.name.empty() ? std::string(buffer) : model.name + "   " + buffer;
    }
};

Renderer::Renderer(const core::Model& model, const RenderOptions& options)
    : impl_(std::make_unique<Impl>(model, options))
{
}

Renderer::~Renderer() = default;

Image Renderer::render(const core::State& state)
{
    return impl_->render(state);
}

void Renderer::frameFrom(const core::State& state)
{
    impl_->frameOnce({state}, true);
}

void Renderer::frameRun(const std::vector<core::State>& states)
{
    impl_->frameOnce(states, false);
}

core::Vec3 Renderer::lightDirection() const
{
    return impl_->light;
}

} // namespace frontier::render
