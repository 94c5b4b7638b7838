// collision/contacts.h: public API of contact detection (FCL, libccd through it).
//
// Convention (one for every pair): a Contact between bodyA and bodyB has a unit normal pointing
// from A towards B (B is pushed along +normal, A along -normal), a depth > 0 when the shapes
// overlap (m), and a world point in the middle of the overlap. bodyA is always a moving body;
// bodyB may be moving or static. The relative normal velocity (v_B - v_A) . n at the point is
// negative when they approach.
#pragma once

#include "core/contact.h"
#include "core/model.h"
#include "core/state.h"

#include <memory>
#include <utility>
#include <vector>

namespace frontier::collision
{

// The contact type and its convention are core's (core/contact.h), so the step pipeline reads
// them without depending on FCL.
using Contact = core::Contact;

// Counters over the detector's lifetime (for --stats and benchmarks).
struct DetectorStats
{
    long detectCalls = 0;      // detect() calls
    long planeTests = 0;       // shape-plane tests that passed the bounding-sphere check
    long broadphasePairs = 0;  // shape pairs from the broadphase allowed by the filter
    long narrowphaseTests = 0; // narrowphase tests: fcl::collide calls and closed-form sphere/capsule pairs
    long separatedPairs = 0;   // broadphase pairs proven apart beyond the margin, skipped
    long contacts = 0;         // contacts reported
};

// How the meshes of moving bodies collide (static bodies' meshes are always triangles).
enum class MovingMeshes
{
    ConvexHulls,     // as their convex hulls of at most cHullCorners corners (collision/README.md
                     // "Meshes"): the default
    FullConvexHulls, // as their convex hulls with every corner (`frontier run --full-hulls`)
    Triangles,       // as triangle meshes (FCL's BVH), for comparison in tests and benchmarks
};

// The most corners a moving mesh's convex hull keeps by default: a larger hull is replaced by the
// hull of cHullCorners of its corners, picked so that it changes least (collision::capConvexHull;
// collision/README.md "Meshes" gives what it changes on real robots).
inline constexpr int cHullCorners = 64;

class ContactDetector final : public core::ContactSource
{
  public:
    // margin: contacts are reported while the shapes are closer than this (m), depth may then
    // be negative (a gap), so that resting contact does not flicker. The convex hulls of moving
    // meshes are computed here, once.
    explicit ContactDetector(const core::Model& model, double margin = 1e-3,
                             MovingMeshes movingMeshes = MovingMeshes::ConvexHulls);
    ~ContactDetector() override;
    ContactDetector(const ContactDetector&) = delete;
    ContactDetector& operator=(const ContactDetector&) = delete;

    // All contacts at the given state; out is cleared first.
    void detect(const core::State& state, std::vector<Contact>& out) override;

    // Body index pairs that may ever collide (after joint, group, ignore and static filtering).
    // Listed as (i, j) with i < j, bodies without collision shapes left out. Computed on the
    // first call (O(bodies^2)), so not meant for the stepping loop.
    const std::vector<std::pair<int, int>>& candidatePairs() const;
    // How many pairs candidatePairs() lists, counted in O(bodies + joints + ignore pairs) without
    // listing them (a large scene has O(bodies^2) of them).
    long long candidatePairCount() const;

    // The time step (s) of the simulation this detector serves, for the swept search
    // (docs/method.md §10): a body whose travel in a step, |v| dt + |w| dt r (r its farthest shape
    // point from its centre of mass), exceeds twice the margin is searched along its motion, so
    // that what lies in its path is reported at the step start as a gap contact. 0 (the default)
    // turns it off; bodies slower than that are searched exactly as without it.
    void setStepTime(double dt);

    double margin() const;
    const DetectorStats& stats() const;

    // The detector's state, defined in collision/detector.h (private to collision/: its narrowphase
    // table names Impl's pair functions).
    struct Impl;

  private:
    std::unique_ptr<Impl> mImpl;
};

// The margin the simulator's detector uses at time step dt (s): contacts are reported while
// shapes are closer than this (m), far enough that a body at 5 m/s cannot cross it in one step
// unseen (speculative contacts, docs/method.md §10), and at least 2 mm, at most 5 cm.
double contactMargin(double dt);

// Pairs of bodies of one robot (core::Model::robots with self-collision on) whose collision shapes
// overlap in the model's initial pose, as (i, j) with i < j, sorted. Loaders add them to
// contact.ignore: such a pair never collides (collision/starting_overlaps.cpp says why).
std::vector<std::pair<int, int>> startingOverlaps(const core::Model& model);

} // namespace frontier::collision
