// bench/peers/mjcf_peers.cpp: an MJCF file in MuJoCo and in Frontier side by side (mjcf_peers.h).
#include "bench/peers/mjcf_peers.h"

#include "bench/peers/harness.h"
#include "bench/peers/mujoco_messages.h"
#include "core/simulator.h"
#include "core/state.h"
#include "io/scene.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <mujoco/mujoco.h>
#include <ostream>
#include <sstream>
#include <stdexcept>

namespace frontier::peers
{

namespace
{
using io::detail::mujocoMat3;
using io::detail::mujocoVec3;

// The offset just past the <mujoco ...> start tag, skipping comments and the XML declaration.
std::size_t afterRootTag(const std::string& text)
{
    std::size_t at = 0;
    while ((at = text.find('<', at)) != std::string::npos)
    {
        if (text.compare(at, 4, "<!--") == 0)
            at = text.find("-->", at);
        else if (text.compare(at, 2, "<?") == 0)
            at = text.find("?>", at);
        else if (text.compare(at, 7, "<mujoco") == 0)
            return text.find('>', at) + 1;
        else
            return std::string::npos;
        if (at == std::string::npos)
            return at;
    }
    return at;
}

// MuJoCo's body name, or Frontier's import's name for an unnamed body.
std::string bodyName(const mjModel* m, int b)
{
    const char* name = mj_id2name(m, mjOBJ_BODY, b);
    return name != nullptr && *name != '\0' ? std::string(name) : "body" + std::to_string(b);
}

// A weld group's mass, centre of mass and inertia about it, world axes, from mjData after forward.
struct Inertial
{
    double mass = 0.0;
    core::Vec3 centre = core::Vec3::Zero();
    core::Mat3 inertia = core::Mat3::Zero();

    // Adds a body of `mass` at `centre` with `inertia` (world axes, about its centre); `finish`
    // after the last.
    void add(double m, const core::Vec3& c, const core::Mat3& i) { parts.push_back({m, c, i}); }
    void finish()
    {
        mass = 0.0;
        centre.setZero();
        for (const Part& p : parts)
        {
            mass += p.mass;
            centre += p.mass * p.centre;
        }
        if (mass > 0.0)
            centre /= mass;
        inertia.setZero();
        for (const Part& p : parts)
        {
            const core::Vec3 d = p.centre - centre;
            inertia += p.inertia + p.mass * (d.squaredNorm() * core::Mat3::Identity() - d * d.transpose());
        }
    }

  private:
    struct Part
    {
        double mass;
        core::Vec3 centre;
        core::Mat3 inertia;
    };
    std::vector<Part> parts;
};

Inertial mujocoGroup(const mjModel* m, const mjData* d, int weld)
{
    Inertial group;
    for (int b = 1; b < m->nbody; ++b)
        if (m->body_weldid[b] == weld)
        {
            const core::Mat3 r = mujocoMat3(d->ximat + 9 * b);
            group.add(m->body_mass[b], mujocoVec3(d->xipos + 3 * b),
                      r * mujocoVec3(m->body_inertia + 3 * b).asDiagonal() * r.transpose());
        }
    group.finish();
    return group;
}

// Frontier's moving bodies by name.
std::map<std::string, int> bodiesByName(const core::Model& model)
{
    std::map<std::string, int> out;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
        if (!model.bodies[i].isStatic)
            out[model.bodies[i].name] = static_cast<int>(i);
    return out;
}

// MuJoCo's model and its data at qpos0 after mj_forward.
struct MujocoAtStart
{
    MujocoModel model;
    io::detail::MujocoData data;
    std::vector<std::string> messages;
};

MujocoAtStart mujocoAtStart(const std::string& path)
{
    MujocoAtStart out;
    const MessageScope scope(out.messages);
    out.model = loadMujocoModel(path);
    out.data.reset(mj_makeData(out.model.get()));
    mj_forward(out.model.get(), out.data.get());
    return out;
}

core::Model frontierModel(const std::string& path)
{
    io::LoadReport report;
    return io::loadScene(path, {}, &report);
}

// The Frontier body of MuJoCo weld group b (by name, as the import names it); throws when absent.
int frontierBodyOf(const std::map<std::string, int>& bodies, const mjModel* m, int b)
{
    const auto found = bodies.find(bodyName(m, b));
    if (found == bodies.end())
        throw std::runtime_error("MuJoCo body '" + bodyName(m, b) +
                                 "' has no moving Frontier body of that name");
    return found->second;
}

core::Mat3 rotation(const core::Quat& q)
{
    return q.normalized().toRotationMatrix();
}

double largestEigenvalue(const core::Mat3& inertia)
{
    return Eigen::SelfAdjointEigenSolver<core::Mat3>(inertia, Eigen::EigenvaluesOnly)
        .eigenvalues()
        .maxCoeff();
}

std::string number(double v, const char* format = "%.3g")
{
    char buffer[48];
    std::snprintf(buffer, sizeof buffer, format, v);
    return buffer;
}

// Some geoms of different bodies, not both welded to the world, whose contype and conaffinity match.
bool contactsPossible(const mjModel* m)
{
    for (int a = 0; a < m->ngeom; ++a)
        for (int b = a + 1; b < m->ngeom; ++b)
        {
            const int wa = m->body_weldid[m->geom_bodyid[a]];
            const int wb = m->body_weldid[m->geom_bodyid[b]];
            if (wa == wb || (wa == 0 && wb == 0))
                continue;
            if ((m->geom_contype[a] & m->geom_conaffinity[b]) ||
                (m->geom_contype[b] & m->geom_conaffinity[a]))
                return true;
        }
    return false;
}

std::string integratorName(int integrator)
{
    switch (integrator)
    {
    case mjINT_EULER:
        return "Euler";
    case mjINT_RK4:
        return "RK4";
    default:
        return "implicit";
    }
}

} // namespace

MujocoModel loadMujocoModel(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw std::runtime_error(path + ": cannot be read");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t root = afterRootTag(text);
    if (root == std::string::npos)
        throw std::runtime_error(path + ": no <mujoco> root element");
    text.insert(root, "<compiler autolimits=\"true\"/>");
    const io::detail::MujocoVfs vfs(new mjVFS);
    mj_defaultVFS(vfs.get());
    if (mj_makeEmptyFileVFS(vfs.get(), path.c_str(), static_cast<int>(text.size())) != 0)
        throw std::runtime_error(path + ": MuJoCo's virtual file system refused it");
    std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), path.c_str())], text.data(), text.size());
    std::string message(4096, '\0');
    MujocoModel model(mj_loadXML(path.c_str(), vfs.get(), message.data(), static_cast<int>(message.size())));
    if (!model)
        throw std::runtime_error(path + ": MuJoCo refused it: " + std::string(message.c_str()));
    return model;
}

MjcfInertia compareInertia(const std::string& path)
{
    const MujocoAtStart mujoco = mujocoAtStart(path);
    const mjModel* m = mujoco.model.get();
    const mjData* d = mujoco.data.get();
    const core::Model model = frontierModel(path);
    const std::map<std::string, int> bodies = bodiesByName(model);

    MjcfInertia out;
    std::map<int, std::size_t> row; // weld group -> out.bodies
    for (int b = 1; b < m->nbody; ++b)
    {
        if (m->body_weldid[b] == 0)
        {
            out.staticMass += m->body_mass[b];
            continue;
        }
        if (m->body_weldid[b] != b)
            continue;
        const int index = frontierBodyOf(bodies, m, b);
        Inertial frontier;
        const int frames = std::max(m->body_jntnum[b] - 1, 0);
        for (int i = index - frames; i <= index; ++i)
        {
            const core::Body& body = model.bodies[static_cast<std::size_t>(i)];
            if (i < index && body.name.rfind(model.bodies[index].name + ":", 0) != 0)
                throw std::runtime_error("Frontier body '" + body.name + "' is not a frame of '" +
                                         model.bodies[index].name + "'");
            const core::Mat3 r = rotation(body.orientation_WB);
            frontier.add(body.mass, body.position_W, r * body.inertia_B * r.transpose());
        }
        frontier.finish();
        const Inertial group = mujocoGroup(m, d, b);
        MjcfBodyInertia entry;
        entry.name = bodyName(m, b);
        entry.mujocoMass = group.mass;
        entry.mujocoCentre_W = group.centre;
        entry.mujocoInertia_W = group.inertia;
        entry.frontierMass = frontier.mass;
        entry.frontierCentre_W = frontier.centre;
        entry.frontierInertia_W = frontier.inertia;
        row[b] = out.bodies.size();
        out.bodies.push_back(entry);
    }
    // What Frontier stores, before its armature terms (mjcf_peers.h) are taken off: the scale of its
    // round-off.
    std::vector<double> storedMass, storedInertia;
    for (const MjcfBodyInertia& entry : out.bodies)
    {
        storedMass.push_back(entry.frontierMass);
        storedInertia.push_back(largestEigenvalue(entry.frontierInertia_W));
    }
    // Frontier's armature terms (mjcf_peers.h), taken off its figures.
    for (int j = 0; j < m->njnt; ++j)
    {
        const double armature = m->dof_armature[m->jnt_dofadr[j]];
        const int b = m->jnt_bodyid[j];
        if (armature == 0.0 || m->jnt_type[j] == mjJNT_FREE || !row.count(m->body_weldid[b]))
            continue;
        MjcfBodyInertia& entry = out.bodies[row.at(m->body_weldid[b])];
        const core::Vec3 axis = mujocoVec3(d->xaxis + 3 * j);
        if (m->jnt_type[j] == mjJNT_HINGE)
            entry.frontierInertia_W -= 0.5 * armature * (core::Mat3::Identity() + axis * axis.transpose());
        else if (m->jnt_type[j] == mjJNT_BALL)
            entry.frontierInertia_W -= armature * core::Mat3::Identity();
        else if (j - m->body_jntadr[b] < m->body_jntnum[b] - 1) // a slide that moves a frame
            entry.frontierMass -= armature;
    }
    const auto note = [&](double difference, const std::string& where)
    {
        if (difference > out.largestDifference || out.largestAt.empty())
        {
            out.largestDifference = difference;
            out.largestAt = where;
        }
    };
    for (std::size_t i = 0; i < out.bodies.size(); ++i)
    {
        MjcfBodyInertia& entry = out.bodies[i];
        out.mujocoMass += entry.mujocoMass;
        out.frontierMass += entry.frontierMass;
        entry.massDifference =
            std::abs(entry.frontierMass - entry.mujocoMass) / std::max(entry.mujocoMass, storedMass[i]);
        entry.centreDifferenceM = (entry.frontierCentre_W - entry.mujocoCentre_W).norm();
        entry.inertiaDifference = (entry.frontierInertia_W - entry.mujocoInertia_W).cwiseAbs().maxCoeff() /
                                  std::max(largestEigenvalue(entry.mujocoInertia_W), storedInertia[i]);
        note(entry.massDifference, entry.name + " mass");
        note(entry.inertiaDifference, entry.name + " inertia");
    }
    if (out.mujocoMass > 0.0)
        note(std::abs(out.frontierMass - out.mujocoMass) / out.mujocoMass, "total mass");
    return out;
}

MjcfMotion compareMotion(const std::string& path, const MjcfMotionSettings& s)
{
    MujocoAtStart mujoco = mujocoAtStart(path);
    mjModel* m = mujoco.model.get();
    mjData* d = mujoco.data.get();
    MjcfMotion out;
    out.contactsPossible = contactsPossible(m);
    m->opt.integrator = mjINT_RK4;
    m->opt.timestep = s.mujocoDt;
    m->opt.disableflags |= mjDSBL_CONTACT;

    core::Model model = frontierModel(path);
    model.simulation.dt = s.frontierDt;
    model.simulation.integrator = s.integrator;
    core::Simulator simulator(model, {}, nullptr); // no contact detection
    core::State state = core::initialState(model);
    const std::map<std::string, int> bodies = bodiesByName(model);

    std::vector<std::pair<int, int>> pairs; // MuJoCo weld group, Frontier body
    for (int b = 1; b < m->nbody; ++b)
        if (m->body_weldid[b] == b)
            pairs.emplace_back(b, frontierBodyOf(bodies, m, b));
    const long mujocoSteps = std::lround(s.sampleEvery / s.mujocoDt);
    const long frontierSteps = std::lround(s.sampleEvery / s.frontierDt);
    const long samples = std::lround(s.duration / s.sampleEvery);
    const MessageScope scope(mujoco.messages);
    std::vector<Pose> start;
    for (long k = 0; k <= samples; ++k)
    {
        if (k > 0)
        {
            for (long i = 0; i < mujocoSteps; ++i)
                mj_step(m, d);
            for (long i = 0; i < frontierSteps; ++i)
                simulator.step(state);
        }
        mj_kinematics(m, d);
        for (std::size_t p = 0; p < pairs.size(); ++p)
        {
            const auto [b, index] = pairs[p];
            const Inertial group = mujocoGroup(m, d, b);
            const core::Vec3 centre = group.mass > 0.0 ? group.centre : mujocoVec3(d->xpos + 3 * b);
            const core::Quat q(mujocoMat3(d->ximat + 9 * b));
            if (k == 0)
                start.push_back({centre, q});
            out.travelM = std::max(out.travelM, (centre - start[p].position_W).norm());
            out.turnRad = std::max(out.turnRad, q.angularDistance(start[p].orientation_WB));
            const double distance = (state.bodies[index].position_W - centre).norm();
            out.maxAngleRad =
                std::max(out.maxAngleRad, state.bodies[index].orientation_WB.angularDistance(q));
            if (distance > out.maxPositionM || out.worstBody.empty())
            {
                out.maxPositionM = distance;
                out.worstBody = bodyName(m, b);
                out.worstTime = static_cast<double>(k) * s.sampleEvery;
            }
        }
    }
    return out;
}

MjcfTiming timeSteps(const std::string& path, double duration, int rounds)
{
    MujocoAtStart mujoco = mujocoAtStart(path);
    const core::Model model = frontierModel(path);
    MjcfTiming out;
    out.frontierDt = model.simulation.dt;
    out.mujocoDt = mujoco.model->opt.timestep;
    out.mujocoIntegrator = integratorName(mujoco.model->opt.integrator);
    const long frontierSteps = std::lround(duration / out.frontierDt);
    const long mujocoSteps = std::lround(duration / out.mujocoDt);
    std::vector<double> frontierTimes, mujocoTimes;
    std::array<int, mjNWARNING> warned{};
    using Clock = std::chrono::steady_clock;
    for (int round = 0; round < rounds; ++round)
    {
        {
            const std::unique_ptr<Engine> engine = makeFrontier(model, core::IntegratorKind::Euler);
            long steps = 0;
            const Clock::time_point start = Clock::now();
            try
            {
                for (; steps < frontierSteps; ++steps)
                    engine->step();
            }
            catch (const std::exception& e)
            {
                out.frontierFailure = "stopped at step " + std::to_string(steps + 1) + ": " + e.what();
            }
            const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
            frontierTimes.push_back(steps > 0 ? 1e6 * seconds / static_cast<double>(steps) : NAN);
        }
        {
            const MessageScope scope(mujoco.messages);
            mj_resetData(mujoco.model.get(), mujoco.data.get());
            const Clock::time_point start = Clock::now();
            for (long i = 0; i < mujocoSteps; ++i)
                mj_step(mujoco.model.get(), mujoco.data.get());
            const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
            mujocoTimes.push_back(1e6 * seconds / static_cast<double>(mujocoSteps));
            for (int w = 0; w < mjNWARNING; ++w)
                warned[static_cast<std::size_t>(w)] += mujoco.data->warning[w].number;
        }
    }
    out.frontierMicroseconds = spread(frontierTimes).median;
    out.mujocoMicroseconds = spread(mujocoTimes).median;
    for (int w = 0; w < mjNWARNING; ++w)
        if (warned[static_cast<std::size_t>(w)] > 0)
            out.mujocoWarnings += (out.mujocoWarnings.empty() ? "" : "; ") +
                                  std::string(mju_warningText(w, mujoco.data->warning[w].lastinfo));
    return out;
}

int runMjcfComparison(const std::string& path, const MjcfMotionSettings& motion, bool noContacts, int rounds,
                      std::ostream& out)
{
    MjcfInertia inertia;
    try
    {
        inertia = compareInertia(path);
    }
    catch (const std::exception& e)
    {
        std::fprintf(stderr, "frontier_peers: %s\n", e.what());
        return 2;
    }
    out << "# " << path << ": Frontier beside MuJoCo " << mj_versionString() << "\n\n";
    out << "Masses and inertias at the start (world frame; Frontier's frames summed into their body, its "
           "armature terms taken off). Total moving mass: MuJoCo "
        << number(inertia.mujocoMass, "%.12g") << " kg, Frontier " << number(inertia.frontierMass, "%.12g")
        << " kg; welded to the world (static): " << number(inertia.staticMass, "%.6g")
        << " kg. Largest relative difference: " << number(inertia.largestDifference) << " ("
        << inertia.largestAt << ").\n\n";
    out << "| body | MuJoCo mass (kg) | Frontier mass (kg) | mass diff (rel.) | centre diff (m) | MuJoCo "
           "inertia diagonal (kg m^2) | inertia diff (rel. to largest eigenvalue) "
           "|\n|---|---|---|---|---|---|---|\n";
    for (const MjcfBodyInertia& b : inertia.bodies)
    {
        const core::Vec3 diagonal = b.mujocoInertia_W.diagonal();
        out << "| " << b.name << " | " << number(b.mujocoMass, "%.9g") << " | "
            << number(b.frontierMass, "%.9g") << " | " << number(b.massDifference) << " | "
            << number(b.centreDifferenceM) << " | " << number(diagonal.x(), "%.4g") << " "
            << number(diagonal.y(), "%.4g") << " " << number(diagonal.z(), "%.4g") << " | "
            << number(b.inertiaDifference) << " |\n";
    }
    try
    {
        const MjcfMotion moved = compareMotion(path, motion);
        out << "\nPassive motion, " << number(motion.duration, "%g") << " s from the start, no control, "
            << "contacts off in both: MuJoCo RK4 at dt " << number(motion.mujocoDt, "%g") << " s, Frontier "
            << core::integratorName(motion.integrator) << " at dt " << number(motion.frontierDt, "%g")
            << " s, compared every " << number(motion.sampleEvery, "%g") << " s: ";
        if (moved.worstBody.empty())
            out << "no moving bodies.\n";
        else if (moved.contactsPossible && !noContacts)
            out << "not run: some geoms may collide (contype/conaffinity); --no-contacts runs it without "
                   "contacts.\n";
        else
            out << "largest centre-of-mass distance " << number(moved.maxPositionM) << " m ("
                << moved.worstBody << " at " << number(moved.worstTime, "%g") << " s), largest angle "
                << number(moved.maxAngleRad) << " rad; in that time MuJoCo's bodies moved up to "
                << number(moved.travelM) << " m and turned up to " << number(moved.turnRad) << " rad"
                << (moved.contactsPossible ? " (geoms may collide: contacts turned off)" : "") << ".\n";
    }
    catch (const std::exception& e)
    {
        out << "\nPassive motion: stopped: " << e.what() << "\n";
    }
    MjcfTiming timing;
    try
    {
        timing = timeSteps(path, 2.0, rounds);
    }
    catch (const std::exception& e)
    {
        out << "\nTime per step: stopped: " << e.what() << "\n";
        return 1;
    }
    out << "\nTime per step, 2 s, the file as loaded (median of " << rounds
        << " alternating rounds): Frontier euler at dt " << number(timing.frontierDt, "%g")
        << " s, contacts on: " << number(timing.frontierMicroseconds) << " us"
        << (timing.frontierFailure.empty() ? "" : " (" + timing.frontierFailure + ")") << "; MuJoCo "
        << timing.mujocoIntegrator << " at dt " << number(timing.mujocoDt, "%g")
        << " s: " << number(timing.mujocoMicroseconds) << " us"
        << (timing.mujocoWarnings.empty() ? "" : " (warnings: " + timing.mujocoWarnings + ")")
        << "; ratio Frontier/MuJoCo " << number(timing.frontierMicroseconds / timing.mujocoMicroseconds)
        << ".\n";
    return 0;
}

} // namespace frontier::peers
