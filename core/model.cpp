// core/model.cpp: names of the model's enums (joint types: core/joints/joint_types.cpp), joint frames,
// and mass properties of shapes.
#include "core/model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace frontier::core
{

int Model::findBody(const std::string& bodyName) const
{
    for (std::size_t i = 0; i < bodies.size(); ++i)
    {
        if (bodies[i].name == bodyName)
        {
            return static_cast<int>(i);
        }
    }
    return -2;
}

namespace
{
// A body's own value of a material property, or none (cWorld has none).
std::optional<double> material(const Model& model, int body, std::optional<double> Body::*property)
{
    return body >= 0 ? model.bodies[static_cast<std::size_t>(body)].*property : std::nullopt;
}
} // namespace

double contactFriction(const Model& model, int a, int b)
{
    const std::optional<double> muA = material(model, a, &Body::friction);
    const std::optional<double> muB = material(model, b, &Body::friction);
    if (!muA && !muB)
    {
        return model.contact.friction; // the scene's, exactly
    }
    const double mixA = muA.value_or(model.contact.friction);
    const double mixB = muB.value_or(model.contact.friction);
    return model.contact.frictionMix == FrictionMix::Larger ? std::max(mixA, mixB) : std::sqrt(mixA * mixB);
}

double contactRestitution(const Model& model, int a, int b)
{
    const double scene = model.contact.restitution;
    return std::max(material(model, a, &Body::restitution).value_or(scene),
                    material(model, b, &Body::restitution).value_or(scene));
}

bool isMovingBody(const Model& model, int body)
{
    return body >= 0 && !model.bodies[static_cast<std::size_t>(body)].isStatic;
}

namespace
{
constexpr SolverInfo cSolvers[] = {
    {SolverKind::Linear, "linear", "O(n), exact (default)"},
    {SolverKind::Dense, "dense", "O(n^3), exact: the oracle linear is checked against"},
    {SolverKind::Pgs, "pgs",
     "projected Gauss-Seidel, a fixed number of sweeps (--pgs-iterations); not exact"},
};
constexpr IntegratorInfo cIntegrators[] = {
    {IntegratorKind::Euler, "euler", "symplectic Euler, first order (default; docs/method.md §4)"},
    {IntegratorKind::Rattle, "rattle", "RATTLE, second order, symplectic (docs/method.md §9)"},
    {IntegratorKind::Rattle4, "rattle4",
     "fourth order (docs/method.md §11), 3 rattle stages a step; a step with contacts or joint limits is one "
     "rattle step, first order across an impact; order 4 for conservative joints only: damping, friction, "
     "servos are first order"},
};

template <class Info> std::vector<std::string> namesOf(std::span<const Info> table)
{
    std::vector<std::string> names;
    for (const Info& info : table)
    {
        names.emplace_back(info.name);
    }
    return names;
}

template <class Info> auto kindFromName(std::span<const Info> table, const std::string& name)
{
    for (const Info& info : table)
    {
        if (name == info.name)
        {
            return std::optional(info.kind);
        }
    }
    return std::optional<decltype(table.front().kind)>();
}

template <class Info, class Kind> const char* nameOf(std::span<const Info> table, Kind kind)
{
    for (const Info& info : table)
    {
        if (info.kind == kind)
        {
            return info.name;
        }
    }
    return "?";
}
} // namespace

std::span<const SolverInfo> solvers()
{
    return cSolvers;
}

std::span<const IntegratorInfo> integrators()
{
    return cIntegrators;
}

std::vector<std::string> solverNames()
{
    return namesOf(solvers());
}

std::vector<std::string> integratorNames()
{
    return namesOf(integrators());
}

std::string nameList(const std::vector<std::string>& names, const std::string& conjunction)
{
    std::string out;
    for (std::size_t k = 0; k < names.size(); ++k)
    {
        out += (k == 0 ? "" : k + 1 == names.size() ? " " + conjunction + " " : ", ") + names[k];
    }
    return out;
}

const char* solverName(SolverKind kind)
{
    return nameOf(solvers(), kind);
}

std::optional<SolverKind> solverFromName(const std::string& name)
{
    return kindFromName(solvers(), name);
}

const char* integratorName(IntegratorKind kind)
{
    return nameOf(integrators(), kind);
}

std::optional<IntegratorKind> integratorFromName(const std::string& name)
{
    return kindFromName(integrators(), name);
}

const char* actuatorTypeName(ActuatorKind kind)
{
    switch (kind)
    {
    case ActuatorKind::Position:
        return "position";
    case ActuatorKind::Velocity:
        return "velocity";
    case ActuatorKind::Effort:
        return "effort";
    }
    return "position";
}

const char* coordinateName(JointCoordinate coordinate)
{
    return coordinate == JointCoordinate::Rotation ? "rotation" : "slide";
}

TripleJump tripleJumpCoefficients()
{
    const double cbrt2 = std::cbrt(2.0);
    return {1.0 / (2.0 - cbrt2), -cbrt2 / (2.0 - cbrt2)};
}

double longestStage(const SimulationSettings& settings)
{
    if (settings.integrator != IntegratorKind::Rattle4)
    {
        return settings.dt;
    }
    return -tripleJumpCoefficients().c2 * settings.dt;
}

namespace
{
// Any unit vector orthogonal to the unit vector n.
Vec3 anyPerpendicular(const Vec3& n)
{
    const Vec3 helper = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    return (helper - helper.dot(n) * n).normalized();
}

struct Frame
{
    Vec3 position = Vec3::Zero();
    Quat rotation = Quat::Identity();
};

Frame bodyFrame(const Model& model, int body)
{
    if (body == cWorld)
    {
        return {};
    }
    const Body& b = model.bodies[static_cast<std::size_t>(body)];
    return {b.position_W, b.orientation_WB};
}
} // namespace

void setJointFrames(const Model& model, Joint& joint, const Vec3& anchor_W, const Vec3& axis_W)
{
    const Frame parent = bodyFrame(model, joint.parent);
    const Frame child = bodyFrame(model, joint.child);
    const Vec3 k_W = axis_W.normalized();
    const Vec3 i_W = anyPerpendicular(k_W);
    const Vec3 j_W = k_W.cross(i_W);

    joint.anchorParent = parent.rotation.conjugate() * (anchor_W - parent.position);
    joint.anchorChild = child.rotation.conjugate() * (anchor_W - child.position);
    joint.axisParent = parent.rotation.conjugate() * k_W;
    joint.perpParent1 = parent.rotation.conjugate() * i_W;
    joint.perpParent2 = parent.rotation.conjugate() * j_W;
    joint.axisChild = child.rotation.conjugate() * k_W;
    joint.perpChild1 = child.rotation.conjugate() * i_W;
    // Universal joint: a1 = d_i in the parent, b2 = d_k x d_i = d_j in the child, so a1 x b2 = d_k.
    joint.angleChildAxis = child.rotation.conjugate() * j_W;
    joint.restRotation_AB = parent.rotation.conjugate() * child.rotation;
}

double shapeVolume(const Shape& shape)
{
    constexpr double pi = std::numbers::pi;
    switch (shape.type)
    {
    case ShapeType::Box:
        return shape.size.prod();
    case ShapeType::Sphere:
        return 4.0 / 3.0 * pi * std::pow(shape.radius, 3);
    case ShapeType::Capsule:
        return pi * shape.radius * shape.radius * (shape.length + 4.0 / 3.0 * shape.radius);
    case ShapeType::Cylinder:
        return pi * shape.radius * shape.radius * shape.length;
    case ShapeType::Plane:
        return 0.0;
    case ShapeType::Mesh:
        return shapeMassProperties(shape, 1.0).mass;
    }
    return 0.0;
}

namespace
{
// Mass properties of a closed triangle mesh of unit density by signed tetrahedra from the origin
// (the divergence theorem; Tonon 2004's canonical tetrahedron covariance).
MassProperties meshMassProperties(const Shape& shape, double density)
{
    double volume = 0.0;
    Vec3 first = Vec3::Zero();
    Mat3 covariance = Mat3::Zero(); // integral of x x^T dV about the origin
    const Mat3 canonical = (Mat3() << 2, 1, 1, 1, 2, 1, 1, 1, 2).finished() / 120.0;
    for (const auto& tri : shape.triangles)
    {
        Mat3 a;
        a.col(0) = shape.vertices[static_cast<std::size_t>(tri[0])];
        a.col(1) = shape.vertices[static_cast<std::size_t>(tri[1])];
        a.col(2) = shape.vertices[static_cast<std::size_t>(tri[2])];
        const double det = a.determinant(); // 6 x signed volume of the tetrahedron
        volume += det / 6.0;
        first += det / 24.0 * (a.col(0) + a.col(1) + a.col(2));
        covariance += det * a * canonical * a.transpose();
    }
    MassProperties out;
    out.mass = density * volume;
    if (volume <= 0.0)
    {
        return out;
    }
    out.centre = first / volume;
    // Shift the covariance to the centre of mass, then I = trace(C) 1 - C.
    const Mat3 c = density * covariance - out.mass * out.centre * out.centre.transpose();
    out.inertia = c.trace() * Mat3::Identity() - c;
    return out;
}
} // namespace

MassProperties shapeMassProperties(const Shape& shape, double density)
{
    constexpr double pi = std::numbers::pi;
    MassProperties out;
    if (shape.type == ShapeType::Mesh)
    {
        return meshMassProperties(shape, density);
    }
    const double m = density * shapeVolume(shape);
    out.mass = m;
    const double r = shape.radius;
    switch (shape.type)
    {
    case ShapeType::Box:
    {
        const Vec3 s2 = shape.size.cwiseProduct(shape.size);
        out.inertia.diagonal() = m / 12.0 * Vec3(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y());
        break;
    }
    case ShapeType::Sphere:
        out.inertia.diagonal().setConstant(0.4 * m * r * r);
        break;
    case ShapeType::Cylinder:
    {
        const double h = shape.length;
        const double ixx = m * (3.0 * r * r + h * h) / 12.0;
        out.inertia.diagonal() = Vec3(ixx, ixx, 0.5 * m * r * r);
        break;
    }
    case ShapeType::Capsule:
    {
        // Cylinder of height h plus two hemispheres whose centres of mass sit 3r/8 beyond the ends.
        const double h = shape.length;
        const double mc = density * pi * r * r * h;
        const double mh = density * 2.0 / 3.0 * pi * r * r * r; // one hemisphere
        const double d = 0.5 * h + 3.0 / 8.0 * r;
        const double ixxCyl = mc * (3.0 * r * r + h * h) / 12.0;
        const double ixxHemi = 83.0 / 320.0 * mh * r * r + mh * d * d;
        const double izz = 0.5 * mc * r * r + 2.0 * 0.4 * mh * r * r;
        out.inertia.diagonal() = Vec3(ixxCyl + 2.0 * ixxHemi, ixxCyl + 2.0 * ixxHemi, izz);
        break;
    }
    case ShapeType::Plane:
    case ShapeType::Mesh:
        break;
    }
    return out;
}

double shapeSupport(const Shape& shape, const Vec3& u_S)
{
    switch (shape.type)
    {
    case ShapeType::Box:
        return 0.5 * shape.size.cwiseAbs().dot(u_S.cwiseAbs());
    case ShapeType::Sphere:
        return shape.radius;
    case ShapeType::Capsule:
        return 0.5 * shape.length * std::abs(u_S.z()) + shape.radius;
    case ShapeType::Cylinder:
        // The rim point furthest along u: half the height along the axis, the radius across it.
        return 0.5 * shape.length * std::abs(u_S.z()) + shape.radius * u_S.head<2>().norm();
    case ShapeType::Mesh:
    {
        double best = -std::numeric_limits<double>::infinity();
        for (const Vec3& v : shape.vertices)
        {
            best = std::max(best, u_S.dot(v));
        }
        return best;
    }
    case ShapeType::Plane:
        return u_S.dot(shape.normal) > 1.0 - 1e-12 ? shape.offset : std::numeric_limits<double>::infinity();
    }
    return 0.0;
}

double shapeReach(const Shape& shape)
{
    switch (shape.type)
    {
    case ShapeType::Box:
        return 0.5 * shape.size.stableNorm();
    case ShapeType::Sphere:
        return shape.radius;
    case ShapeType::Capsule:
        return shape.radius + 0.5 * shape.length;
    case ShapeType::Cylinder:
        return std::hypot(shape.radius, 0.5 * shape.length);
    case ShapeType::Mesh:
    {
        double farthest = 0.0; // NaN-safe: a non-finite vertex makes it infinite
        for (const Vec3& v : shape.vertices)
        {
            const double d = v.stableNorm(); // no overflow of the squares for a huge vertex
            farthest =
                d <= farthest ? farthest : (std::isnan(d) ? std::numeric_limits<double>::infinity() : d);
        }
        return farthest;
    }
    case ShapeType::Plane:
        return std::abs(shape.offset);
    }
    return 0.0;
}

double shapeSupportWorld(const Shape& shape, const Vec3& bodyPosition_W, const Quat& bodyOrientation_WB,
                         const Vec3& u_W)
{
    if (shape.type == ShapeType::Plane) // planes are posed in the world already
    {
        return shapeSupport(shape, u_W);
    }
    const Quat q_WS = bodyOrientation_WB * shape.rotation_BS;
    const Vec3 origin_W = bodyPosition_W + bodyOrientation_WB * shape.position_BS;
    return u_W.dot(origin_W) + shapeSupport(shape, q_WS.conjugate() * u_W);
}

} // namespace frontier::core
