// core/contact.h: contact points as the solver sees them, and the interface of a contact source
// (collision/ implements it with FCL; core does not depend on collision/).
//
// Convention: normal_W points from bodyA towards bodyB (B is pushed along +n, A along -n);
// depth > 0 when the shapes overlap (m), < 0 for a gap within the detector's margin; point_W in
// the middle of the overlap. bodyA moves; bodyB may be moving or static.
#pragma once

#include "core/state.h"

#include <vector>

namespace frontier::core
{

struct Contact
{
    int bodyA = 0;                 // moving body index
    int bodyB = 0;                 // moving or static body index
    Vec3 point_W = Vec3::Zero();   // m
    Vec3 normal_W = Vec3::UnitZ(); // unit, from A towards B
    double depth = 0.0;            // m, > 0 when penetrating
};

// A contact of a step with the impulse it passed over that step (N s, world frame): what body B
// received from body A (A received the opposite). The normal part is >= 0 (contacts push, never
// pull); the rest is friction, tangential to the contact.
struct ContactImpulse
{
    Contact contact;
    Vec3 impulse_W = Vec3::Zero(); // N s, on B

    double normalImpulse() const { return contact.normal_W.dot(impulse_W); }
    Vec3 frictionImpulse_W() const { return impulse_W - normalImpulse() * contact.normal_W; }
};

class ContactSource
{
  public:
    virtual ~ContactSource() = default;
    // All contacts at the given state; out is cleared first.
    virtual void detect(const State& state, std::vector<Contact>& out) = 0;
};

} // namespace frontier::core
