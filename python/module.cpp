// python/module.cpp: the C++ part of the Python module `frontier` (frontier._frontier): load(),
// Simulator, Recording, and the translation of the library's errors into the exceptions of
// python/frontier/_errors.py. Arrays are NumPy copies made at each read (python/arrays.h).
#include "core/impulse_solver.h"
#include "io/atomic_file.h"
#include "python/arrays.h"
#include "python/simulator.h"
#include "render/renderer.h"
#include "run/names.h"

#include <cmath>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <utility>

namespace py = pybind11;
using namespace pybind11::literals;

namespace frontier::python
{

namespace
{

// Text from the library as a Python str: names and messages may hold bytes that are not UTF-8
// (a scene's own names), shown as \xNN rather than failing to convert.
py::str text(const std::string& value)
{
    return py::reinterpret_steal<py::str>(
        PyUnicode_DecodeUTF8(value.data(), static_cast<py::ssize_t>(value.size()), "backslashreplace"));
}

py::list texts(const std::vector<std::string>& values)
{
    py::list out;
    for (const std::string& value : values)
    {
        out.append(text(value));
    }
    return out;
}

py::object errorClass(const char* name)
{
    return py::module_::import("frontier._errors").attr(name);
}

void raise(const py::object& type, const py::object& error)
{
    PyErr_SetObject(type.ptr(), error.ptr());
}

void translateErrors(std::exception_ptr thrown)
{
    try
    {
        if (thrown)
        {
            std::rethrow_exception(thrown);
        }
    }
    catch (const io::InputError& e)
    {
        const py::object type = errorClass("LoadError");
        raise(type, type(text(e.what()), text(e.file()), e.line(), e.column(), text(e.message())));
    }
    catch (const core::SimulationError& e)
    {
        const core::SimulationFailure& f = e.failure();
        const py::object type = errorClass("SimulationError");
        raise(type, type(text(e.what()), f.step, f.time, text(f.bodyName), f.quantity,
                         f.joint ? py::object(text(f.jointName)) : py::object(py::none())));
    }
    catch (const core::SingularJointError& e)
    {
        const py::object type = errorClass("SimulationError");
        raise(type, type(text(e.what()), py::none(), py::none(), py::none(), "singular joint",
                         text(e.jointName())));
    }
    catch (const run::NameError& e)
    {
        const py::object type = errorClass("UnknownNameError");
        raise(type, type(text(e.what())));
    }
    catch (const io::OutputError& e)
    {
        PyErr_SetObject(PyExc_OSError, text(e.what()).ptr());
    }
}

// A body given by name or index.
// An index given as a Python int (numpy integers too), within [0, count); `what` names it.
int indexOf(const py::object& value, std::size_t count, const std::string& what)
{
    if (!py::isinstance<py::int_>(value) && !py::hasattr(value, "__index__"))
    {
        throw py::type_error(what + ": expected a name (str) or an index (int), not " +
                             py::str(py::type::of(value).attr("__name__")).cast<std::string>());
    }
    const long long index = py::int_(value).cast<long long>();
    if (index < 0 || static_cast<unsigned long long>(index) >= count)
    {
        throw py::index_error(what + " index " + std::to_string(index) + " out of range (the model has " +
                              std::to_string(count) + ")");
    }
    return static_cast<int>(index);
}

int bodyOf(const Simulator& sim, const py::object& body)
{
    if (py::isinstance<py::str>(body))
    {
        return sim.bodyIndex(body.cast<std::string>());
    }
    return indexOf(body, sim.model().bodies.size(), "body");
}

// f(), with a std::runtime_error of a file (libpng's) raised as OSError.
template <typename F> auto asOSError(F f)
{
    try
    {
        return f();
    }
    catch (const py::builtin_exception&) // a ValueError of the arguments stays one
    {
        throw;
    }
    catch (const std::runtime_error& e)
    {
        PyErr_SetObject(PyExc_OSError, text(e.what()).ptr());
        throw py::error_already_set();
    }
}

// A path given as str or path-like (pathlib.Path), "" for None.
std::string pathOf(const py::object& path)
{
    return path.is_none() ? std::string()
                          : py::module_::import("os").attr("fspath")(path).cast<std::string>();
}

int actuatorOf(const Simulator& sim, const py::object& actuator)
{
    if (py::isinstance<py::str>(actuator))
    {
        return sim.actuatorIndex(actuator.cast<std::string>());
    }
    return indexOf(actuator, sim.model().actuators.size(), "actuator");
}

std::optional<core::Camera> cameraOf(const py::object& camera)
{
    if (camera.is_none())
    {
        return std::nullopt;
    }
    const py::dict d = camera.cast<py::dict>();
    core::Camera c;
    c.automatic = false;
    for (const auto& [key, value] : d)
    {
        if (!py::isinstance<py::str>(key))
        {
            throw py::type_error("camera: keys are position, look_at and fov");
        }
        const std::string k = key.cast<std::string>();
        if (k == "position")
        {
            c.position = vec3Of(value.cast<py::object>(), "camera position");
        }
        else if (k == "look_at")
        {
            c.lookAt = vec3Of(value.cast<py::object>(), "camera look_at");
        }
        else if (k == "fov")
        {
            c.fovDegrees = value.cast<double>();
        }
        else
        {
            throw py::key_error("camera: unknown key '" + k + "' (expected position, look_at, fov)");
        }
    }
    if (!d.contains("position") || !d.contains("look_at"))
    {
        throw py::value_error("camera: expected position and look_at (m), and fov (degrees) if not 45");
    }
    if (!(std::isfinite(c.fovDegrees) && c.fovDegrees > 0.0 && c.fovDegrees < 180.0))
    {
        throw py::value_error("camera fov: expected a number of degrees in (0, 180)");
    }
    if ((c.position - c.lookAt).norm() < 1e-9)
    {
        throw py::value_error("camera: position and look_at must differ");
    }
    return c;
}

// The handle of a recording under way (Simulator.record()).
class RecordingHandle
{
  public:
    explicit RecordingHandle(Simulator& sim) : mSim(&sim) {}
    RecordingHandle(RecordingHandle&& other) noexcept : mSim(std::exchange(other.mSim, nullptr)) {}
    RecordingHandle& operator=(RecordingHandle&&) = delete;
    // Dropped without close(): the recording ends and writes nothing (the simulator can record again).
    ~RecordingHandle()
    {
        if (mSim != nullptr && mSim->recording())
        {
            mSim->discardRecording();
        }
    }

    py::list close(const std::optional<std::string>& failure)
    {
        py::list written;
        if (mSim != nullptr)
        {
            Simulator* sim = std::exchange(mSim, nullptr);
            for (const std::string& path : sim->closeRecording(failure))
            {
                written.append(text(path));
            }
        }
        return written;
    }

  private:
    Simulator* mSim; // null once closed; kept alive by the handle (py::keep_alive)
};

std::unique_ptr<Simulator> load(const std::string& path, bool fixedBase, bool freeBase,
                                std::optional<double> dropHeight, bool hold,
                                const std::vector<std::string>& packagePath,
                                const std::map<std::string, double>& jointPositions,
                                std::optional<bool> selfCollision, std::optional<double> dt,
                                std::optional<std::string> integrator, std::optional<std::string> solver,
                                std::optional<int> pgsIterations, std::optional<std::string> keyframe)
{
    LoadOptions options;
    options.urdf.fixedBase = fixedBase;
    options.urdf.freeBase = freeBase;
    options.urdf.dropHeight = dropHeight;
    options.urdf.hold = hold;
    options.urdf.packagePaths = packagePath;
    options.urdf.jointPositions = jointPositions;
    options.urdf.selfCollision = selfCollision;
    options.urdf.keyframe = keyframe;
    options.overrides.dt = dt;
    options.overrides.integrator = integrator;
    options.overrides.solver = solver;
    options.overrides.pgsIterations = pgsIterations;
    py::gil_scoped_release release; // other threads go on while the files are read
    return std::make_unique<Simulator>(path, options);
}

// load()'s docstring; the integrator and solver names come from core's tables.
std::string quotedNames(const std::vector<std::string>& names)
{
    std::string out;
    for (const std::string& name : names)
    {
        out += (out.empty() ? "\"" : ", \"") + name + "\"";
    }
    return out;
}

std::string loadDoc()
{
    return R"(load(path, *, fixed_base=False, free_base=False, drop_height=None, hold=False,
     package_path=(), joint_positions=None, self_collision=None, dt=None, integrator=None,
     solver=None, pgs_iterations=None, keyframe=None) -> Simulator

Loads a YAML scene, a URDF robot or an MJCF model exactly as `frontier run PATH` does with the matching flags:
fixed_base (weld a bare URDF's root where it is), free_base, drop_height (m: lowest collision
point above the floor), hold (a position servo on every joint coordinate without an actuator,
holding its starting position), package_path (folders searched for package:// URIs before
ROS_PACKAGE_PATH), joint_positions ({joint name: rad or m}), self_collision (bool), dt (s),
integrator ()" +
           quotedNames(frontier::core::integratorNames()) + "), solver (" +
           quotedNames(frontier::core::solverNames()) + R"(), pgs_iterations,
keyframe (the name of a bare MJCF file's <key> to start from).
Warnings of the load go to stderr as the command line prints them.

Raises frontier.LoadError (file, line, column, message) for a file that cannot be loaded or a
keyword out of range.)";
}

constexpr const char* cSimulatorDoc = R"(A loaded scene and its state, stepped at a fixed time step.

Bodies are indexed in the model's order (body_names), static ones included; joint coordinates
(the rotation of revolute joints, the slide of prismatic ones, both of cylindrical ones) in
coordinate_names order; actuators in actuator_names order. Every array property returns a new
NumPy array (a copy: it does not change when the simulation steps on, and writing to it changes
nothing). Units: m, s, kg, rad, N, N m.)";

void bindState(py::module_& m)
{
    py::class_<SavedState>(m, "State",
                           "A saved state (Simulator.get_state()), restored with Simulator.set_state().")
        .def_property_readonly(
            "time", [](const SavedState& s) { return s.snapshot.state.time; }, "Its simulated time (s).")
        .def_property_readonly(
            "steps_taken", [](const SavedState& s) { return s.snapshot.state.step; }, "Its step count.")
        .def("__copy__", [](const SavedState& s) { return s; })
        .def("__deepcopy__", [](const SavedState& s, const py::dict&) { return s; });
}

void bindRecording(py::module_& m)
{
    py::class_<RecordingHandle>(m, "Recording", "A recording under way (Simulator.record()).")
        .def(
            "close", [](RecordingHandle& r) { return r.close(std::nullopt); },
            "Writes the files; returns their paths. Closing twice does nothing.")
        .def("__enter__", [](RecordingHandle& r) -> RecordingHandle& { return r; })
        .def("__exit__",
             [](RecordingHandle& r, const py::object& type, const py::object& value, const py::object&)
             {
                 std::optional<std::string> failure;
                 if (!type.is_none())
                 {
                     failure = "stopped by " + py::str(type.attr("__name__")).cast<std::string>() + ": " +
                               py::str(value).cast<std::string>();
                 }
                 r.close(failure);
                 return false;
             });
}

// Simulator.step and the clock and settings it advances under.
void bindStepping(py::class_<Simulator>& simulator)
{
    simulator
        .def(
            "step",
            [](Simulator& s, long n)
            {
                if (n < 0)
                {
                    throw py::value_error("step(n): n must be >= 0, not " + std::to_string(n));
                }
                py::gil_scoped_release release;
                s.step(n,
                       []
                       {
                           py::gil_scoped_acquire acquire;
                           if (PyErr_CheckSignals() != 0)
                           {
                               throw py::error_already_set();
                           }
                       });
            },
            "n"_a = 1,
            "Takes n steps of dt (s). Releases the GIL while stepping; Ctrl-C stops a long call between "
            "steps. Raises frontier.SimulationError when a step blows up (the state is then that of the "
            "failed step; restore a saved one with set_state).")
        .def_property_readonly(
            "time", [](const Simulator& s) { return s.state().time; },
            "Simulated time (s), exactly steps_taken * dt.")
        .def_property_readonly(
            "dt", [](const Simulator& s) { return s.model().simulation.dt; }, "The time step (s).")
        .def_property_readonly(
            "steps_taken", [](const Simulator& s) { return s.state().step; }, "Steps taken since the start.")
        .def_property_readonly(
            "path", [](const Simulator& s) { return s.path(); }, "The scene or model file loaded.")
        .def_property(
            "gravity", [](const Simulator& s) { return vec3Array(s.model().simulation.gravity); },
            [](Simulator& s, const py::object& g) { s.setGravity(vec3Of(g, "gravity")); },
            "Gravity (3,) in m/s^2, world frame; setting it acts from the next step on.");
}

// The names (and static properties) of the bodies, joints and actuators.
void bindNames(py::class_<Simulator>& simulator)
{
    simulator
        .def_property_readonly(
            "body_names", [](const Simulator& sim) { return texts(bodyNames(sim)); },
            "Names of the bodies, in index order.")
        .def_property_readonly("is_static", &staticMask,
                               "(n,) bool: the body never moves (the floor, a welded base).")
        .def_property_readonly("masses", &masses, "(n,) kg.")
        .def_property_readonly(
            "joint_names", [](const Simulator& sim) { return texts(jointNames(sim)); },
            "Names of the joints, in index order.")
        .def_property_readonly(
            "coordinate_names", [](const Simulator& sim) { return texts(coordinateNames(sim)); },
            "Names of the joint coordinates: the joint's name, or NAME:slide and "
            "NAME:rotation for a cylindrical joint. Ball and free joints have none.")
        .def_property_readonly(
            "actuator_names", [](const Simulator& sim) { return texts(actuatorNames(sim)); },
            "Names of the actuators: the coordinate each drives (coordinate_names).")
        .def_property_readonly("actuator_kinds", &actuatorKinds,
                               "Per actuator: position, velocity or effort.");
}

// What the state and the last step give: poses, velocities, contacts, efforts, energy.
void bindOutputs(py::class_<Simulator>& simulator)
{
    simulator
        .def_property_readonly("positions", &positions, "(n, 3) float64: centres of mass (m), world frame.")
        .def_property_readonly("orientations", &orientations,
                               "(n, 4) float64: unit quaternions w, x, y, z, body to world (as in the CSV).")
        .def_property_readonly("velocities", &velocities, "(n, 3) float64: centre-of-mass velocities (m/s).")
        .def_property_readonly("angular_velocities", &angularVelocities,
                               "(n, 3) float64: angular velocities (rad/s), world frame.")
        .def_property_readonly("joint_positions", &jointPositions,
                               "(k,) float64 per coordinate_names: rad or m, counted as the model file "
                               "counts them (a URDF joint's position).")
        .def_property_readonly("joint_velocities", &jointVelocities, "(k,) float64: rad/s or m/s.")
        .def_property_readonly("contacts", &contacts,
                               "The contacts of the last step as a structured array: body_a, body_b (int32 "
                               "indices), point (3, m), normal (3, unit, from a towards b), depth (m, < 0 a "
                               "gap within the margin), force (3, N: the impulse body b received over the "
                               "step / dt, world frame). Empty before the first step and after set_state.")
        .def_property_readonly("joint_wrenches", &jointWrenches,
                               "(j, 6) float64: per joint, what it passed to its child body over the last "
                               "step / dt: force (N) then torque about the joint's anchor (N m), world "
                               "frame. Zero before the first step and after set_state.")
        .def_property_readonly("actuator_efforts", &actuatorEfforts,
                               "(a,) float64: each actuator's effort over the last step (N m or N, along "
                               "its coordinate).")
        .def_property_readonly(
            "energy", [](const Simulator& s) { return core::totalEnergy(s.model(), s.state()); },
            "Kinetic plus gravitational potential energy of the moving bodies (J).")
        .def_property_readonly(
            "joint_error", [](Simulator& s) { return s.jointErrors(); },
            "(m, rad): the largest violation of a joint's conditions in the current state.");
}

// External pushes, saving and restoring the state, body look-up.
void bindForcesAndSaving(py::class_<Simulator>& simulator)
{
    simulator
        .def(
            "apply_force",
            [](Simulator& s, const py::object& body, const py::object& force, const py::object& torque,
               const py::object& point)
            {
                s.applyForce(bodyOf(s, body), vec3Of(force, "force"),
                             torque.is_none() ? core::Vec3::Zero() : vec3Of(torque, "torque"),
                             point.is_none() ? std::nullopt : std::optional(vec3Of(point, "point")));
            },
            "body"_a, "force"_a, "torque"_a = py::none(), "point"_a = py::none(),
            "Pushes a moving body (name or index) during the next step only: force (N) through its "
            "centre of mass, or at `point` (m, world), and torque (N m), world frame. Calls before "
            "one step add up; the step's impulse is force * dt whatever the integrator.")
        .def("get_state", &Simulator::getState,
             "Saves what the next steps depend on: poses, velocities, time, joint angles, the contact "
             "solver's warm start and cached matrices, actuator targets and limit states, pending "
             "forces (not gravity, which belongs to the model). Cheap: microseconds.")
        .def("set_state", &Simulator::setState, "state"_a,
             "Restores a state from get_state (of this simulator or another loaded from the same "
             "file): the same steps then give the same states, bit for bit.")
        .def("body_index", &Simulator::bodyIndex, "name"_a, "The index of the body named so.");
}

// Actuator targets.
void bindActuators(py::class_<Simulator>& simulator)
{
    simulator
        .def(
            "set_actuator_target",
            [](Simulator& s, const py::object& actuator, double value)
            { s.setActuatorTarget(actuatorOf(s, actuator), value); },
            "actuator"_a, "value"_a,
            "Sets an actuator's target from the next step on: by name (actuator_names, the driven "
            "joint's name) or index. rad or m for a position servo (as the model file counts the "
            "joint), rad/s or m/s for a velocity motor, N m or N for an effort actuator.")
        .def(
            "set_actuator_targets",
            [](Simulator& s, const py::array_t<double, py::array::c_style | py::array::forcecast>& values)
            {
                if (values.ndim() != 1 ||
                    static_cast<std::size_t>(values.shape(0)) != s.model().actuators.size())
                {
                    throw py::value_error("set_actuator_targets: expected " +
                                          std::to_string(s.model().actuators.size()) +
                                          " values, one per actuator_names entry");
                }
                for (py::ssize_t a = 0; a < values.shape(0); ++a) // all checked before any is set
                {
                    if (!std::isfinite(values.at(a)))
                    {
                        throw py::value_error("set_actuator_targets: the target of '" +
                                              s.actuatorName(static_cast<std::size_t>(a)) +
                                              "' must be finite");
                    }
                }
                for (py::ssize_t a = 0; a < values.shape(0); ++a)
                {
                    s.setActuatorTarget(static_cast<int>(a), values.at(a));
                }
            },
            "values"_a,
            "Sets every actuator's target at once, in actuator_names order (units as set_actuator_target).");
}

// Images of the current state and recordings of the steps to come.
void bindRenderingAndRecording(py::class_<Simulator>& simulator)
{
    simulator
        .def(
            "render",
            [](Simulator& s, int width, int height, const py::object& camera)
            {
                const std::optional<core::Camera> view = cameraOf(camera);
                render::Image image;
                {
                    py::gil_scoped_release release;
                    image = s.render(width, height, view);
                }
                return imageArray(image);
            },
            "width"_a = 640, "height"_a = 480, "camera"_a = py::none(),
            "The current state drawn by the OSMesa renderer of `frontier render`: an (height, width, 3) "
            "uint8 array. camera: None for the scene's camera (or one framed around the bodies at the "
            "first render, then kept), or a dict with position (m), look_at (m) and fov (degrees).")
        .def(
            "record",
            [](Simulator& s, const py::object& trajectory, const py::object& stats, int every)
            {
                s.startRecording({{}, {}, pathOf(trajectory), pathOf(stats), every});
                return RecordingHandle(s);
            },
            "trajectory"_a = py::none(), "stats"_a = py::none(), "every"_a = 1, py::keep_alive<0, 1>(),
            "Records the steps from now on into the files `frontier run --trajectory --stats` writes "
            "(so `frontier check` and `frontier render` read them): a row block every `every` steps. "
            "Returns a Recording; use it in a with statement, or call close(). The files appear "
            "when it is closed; a loop that raised leaves its rows under NAME.failed.csv and stats "
            "with completed: false. `frontier check` reruns the scene file: it matches a recording "
            "started at time 0 of a loop that only stepped.");
}

void bindSimulator(py::module_& m)
{
    py::class_<Simulator> simulator(m, "Simulator", cSimulatorDoc);
    bindStepping(simulator);
    bindNames(simulator);
    bindOutputs(simulator);
    bindForcesAndSaving(simulator);
    bindActuators(simulator);
    bindRenderingAndRecording(simulator);
}

} // namespace

} // namespace frontier::python

PYBIND11_MODULE(_frontier, m)
{
    using namespace frontier::python;
    m.doc() = "Frontier's C++ part; use the package `frontier`.";
    m.attr("__version__") = FRONTIER_VERSION;
    py::register_exception_translator(&translateErrors);
    registerArrayTypes();
    bindState(m);
    bindRecording(m);
    bindSimulator(m);
    m.def(
        "write_png",
        [](const py::object& path, const py::object& image)
        { asOSError([&] { frontier::render::writePng(pathOf(path), imageOf(image)); }); },
        "path"_a, "image"_a,
        "Writes an (h, w, 3) or (h, w, 4) uint8 array (a render()) as a PNG file, through a temporary "
        "file renamed into place.");
    m.def(
        "read_png",
        [](const py::object& path)
        { return imageArray(asOSError([&] { return frontier::render::readPng(pathOf(path)); })); },
        "path"_a, "Reads a PNG file (a frame of `frontier render`) as an (h, w, 3) uint8 array.");
    static const std::string cLoadDoc = loadDoc(); // pybind11 keeps the pointer
    m.def("load", &load, cLoadDoc.c_str(), "path"_a, py::kw_only(), "fixed_base"_a = false,
          "free_base"_a = false, "drop_height"_a = py::none(), "hold"_a = false,
          "package_path"_a = std::vector<std::string>{},
          "joint_positions"_a = std::map<std::string, double>{}, "self_collision"_a = py::none(),
          "dt"_a = py::none(), "integrator"_a = py::none(), "solver"_a = py::none(),
          "pgs_iterations"_a = py::none(), "keyframe"_a = py::none());
}
