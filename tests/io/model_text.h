// tests/io/model_text.h: every field of a loaded scene (core::Model and io::LoadReport) as text,
// numbers in hexadecimal floating point, so that two loads compare field by field and exactly: the
// first differing line names the field.
#pragma once

#include "core/model.h"
#include "io/scene.h"

#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace frontier::io::test
{

namespace model_text_detail
{
inline std::string number(double x)
{
    char text[64];
    std::snprintf(text, sizeof text, "%a", x);
    return text;
}

template <class Matrix> std::string numbers(const Matrix& m)
{
    std::string out = "[";
    for (int i = 0; i < static_cast<int>(m.size()); ++i)
    {
        out += (i > 0 ? " " : "") + number(m.data()[i]);
    }
    return out + "]";
}

inline std::string numbers(const std::vector<double>& v)
{
    std::string out = "[";
    for (std::size_t i = 0; i < v.size(); ++i)
    {
        out += (i > 0 ? " " : "") + number(v[i]);
    }
    return out + "]";
}

inline std::string quaternion(const core::Quat& q)
{
    return numbers(q.coeffs());
}

inline void shape(std::ostringstream& out, const std::string& at, const core::Shape& s)
{
    out << at << ".type " << static_cast<int>(s.type) << "\n"
        << at << ".size " << numbers(s.size) << "\n"
        << at << ".radius " << number(s.radius) << "\n"
        << at << ".length " << number(s.length) << "\n"
        << at << ".normal " << numbers(s.normal) << "\n"
        << at << ".offset " << number(s.offset) << "\n"
        << at << ".meshFile " << s.meshFile << "\n"
        << at << ".vertices " << s.vertices.size() << "\n";
    for (std::size_t v = 0; v < s.vertices.size(); ++v)
    {
        out << at << ".vertex " << v << " " << numbers(s.vertices[v]) << "\n";
    }
    for (std::size_t t = 0; t < s.triangles.size(); ++t)
    {
        out << at << ".triangle " << t << " " << s.triangles[t][0] << " " << s.triangles[t][1] << " "
            << s.triangles[t][2] << "\n";
    }
    out << at << ".position_BS " << numbers(s.position_BS) << "\n"
        << at << ".rotation_BS " << quaternion(s.rotation_BS) << "\n";
}

inline std::string function(const core::TimeFunction& f)
{
    return std::to_string(static_cast<int>(f.kind)) + " " + number(f.constant) + " " + number(f.amplitude) +
           " " + number(f.frequency) + " " + number(f.phase) + " " + number(f.offset) + " " +
           numbers(f.times) + " " + numbers(f.values) + " " + numbers(f.slopes);
}
} // namespace model_text_detail

inline std::string modelText(const core::Model& model, const LoadReport* report = nullptr)
{
    using namespace model_text_detail;
    std::ostringstream out;
    out << "name " << model.name << "\nsourceFile " << model.sourceFile << "\n";
    const core::SimulationSettings& sim = model.simulation;
    out << "simulation " << number(sim.dt) << " " << number(sim.duration) << " " << numbers(sim.gravity)
        << " " << static_cast<int>(sim.solver) << " " << sim.pgsIterations << " "
        << static_cast<int>(sim.integrator) << "\n";
    out << "contact " << number(model.contact.friction) << " " << number(model.contact.restitution) << "\n";
    for (const auto& pair : model.contact.ignore)
    {
        out << "contact.ignore " << pair[0] << " " << pair[1] << "\n";
    }
    const core::Camera& camera = model.camera;
    out << "camera " << camera.automatic << " " << numbers(camera.position) << " " << numbers(camera.lookAt)
        << " " << number(camera.fovDegrees) << "\n";
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        const core::Body& b = model.bodies[i];
        const std::string at = "body " + std::to_string(i);
        out << at << ".name " << b.name << "\n"
            << at << ".isStatic " << b.isStatic << "\n"
            << at << ".mass " << number(b.mass) << "\n"
            << at << ".inertia_B " << numbers(b.inertia_B) << "\n";
        for (std::size_t s = 0; s < b.shapes.size(); ++s)
        {
            shape(out, at + ".shape " + std::to_string(s), b.shapes[s]);
        }
        for (std::size_t s = 0; s < b.visuals.size(); ++s)
        {
            shape(out, at + ".visual " + std::to_string(s), b.visuals[s]);
        }
        out << at << ".color " << (b.color ? numbers(*b.color) : "none") << "\n"
            << at << ".group " << b.group << "\n"
            << at << ".position_W " << numbers(b.position_W) << "\n"
            << at << ".orientation_WB " << quaternion(b.orientation_WB) << "\n"
            << at << ".velocity_W " << numbers(b.velocity_W) << "\n"
            << at << ".angularVelocity_W " << numbers(b.angularVelocity_W) << "\n";
    }
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        const core::Joint& j = model.joints[k];
        const std::string at = "joint " + std::to_string(k);
        out << at << ".name " << j.name << "\n"
            << at << ".type " << static_cast<int>(j.type) << " parent " << j.parent << " child " << j.child
            << "\n"
            << at << ".anchors " << numbers(j.anchorParent) << " " << numbers(j.anchorChild) << "\n"
            << at << ".axes " << numbers(j.axisParent) << " " << numbers(j.perpParent1) << " "
            << numbers(j.perpParent2) << " " << numbers(j.axisChild) << " " << numbers(j.perpChild1) << " "
            << numbers(j.angleChildAxis) << "\n"
            << at << ".restRotation_AB " << quaternion(j.restRotation_AB) << "\n"
            << at << ".limits "
            << (j.limits ? number((*j.limits)[0]) + " " + number((*j.limits)[1]) : std::string("none"))
            << "\n"
            << at << ".coordinate " << number(j.initialPosition) << " " << number(j.damping) << " "
            << number(j.friction) << " " << number(j.effortLimit) << " " << j.collideConnected << "\n";
    }
    for (const core::Robot& r : model.robots)
    {
        out << "robot " << r.name << " " << r.sourceFile << " " << r.firstBody << " " << r.bodyCount << " "
            << r.selfCollision << "\n";
    }
    for (const core::Actuator& a : model.actuators)
    {
        out << "actuator " << a.joint << " " << static_cast<int>(a.coordinate) << " "
            << static_cast<int>(a.kind) << " " << number(a.kp) << " " << number(a.kd) << " "
            << number(a.effortLimit) << " " << function(a.target) << "\n";
    }
    for (const core::Load& l : model.loads)
    {
        out << "load " << l.body << " " << static_cast<int>(l.frame) << " " << numbers(l.force) << " "
            << numbers(l.torque) << " " << (l.point ? numbers(*l.point) : "none") << " " << number(l.from)
            << " " << number(l.to) << " " << (l.instant ? number(*l.instant) : "none") << "\n";
    }
    if (report != nullptr)
    {
        for (const std::string& w : report->warnings)
        {
            out << "warning " << w << "\n";
        }
        for (const RobotReport& r : report->robots)
        {
            out << "report.robot " << r.name << " " << r.prefix << " " << r.file << " " << r.links << " "
                << r.placement << "\n";
            for (const auto& [a, b] : r.welded)
            {
                out << "report.welded " << a << " " << b << "\n";
            }
            for (const std::string& s : r.repaired)
            {
                out << "report.repaired " << s << "\n";
            }
            for (const auto& [a, b] : r.excluded)
            {
                out << "report.excluded " << a << " " << b << "\n";
            }
        }
        if (report->reference)
        {
            out << "reference " << report->reference->csvPath << " " << report->reference->body << "\n";
        }
        if (report->stability)
        {
            const SceneStabilityCriteria& c = *report->stability;
            out << "stability " << (c.maxSpeed ? number(*c.maxSpeed) : "none") << " "
                << (c.maxEnergyRise ? number(*c.maxEnergyRise) : "none") << "\n";
            for (const StabilityJointCheck& j : c.joints)
            {
                out << "stability.joint " << j.joint << " "
                    << (j.maxTrackingError ? number(*j.maxTrackingError) : "none") << " "
                    << (j.range ? number((*j.range)[0]) + " " + number((*j.range)[1]) : std::string("none"))
                    << " " << (j.reach ? number(*j.reach) : "none") << "\n";
            }
        }
    }
    return out.str();
}

} // namespace frontier::io::test
