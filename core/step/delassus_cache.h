// core/step/delassus_cache.h: the Delassus matrix G of a step's extra rows (core/delassus.h), whose
// parts are kept from step to step while their rows stay (docs/method.md §5).
//
// G is stored by tree. A tree whose rows are those of a recent step (the same contacts within
// cReuseDistance and cReuseTurn, the same joint rows, built at most cMaxAge steps ago) keeps that
// step's part as it was: G~, approximate, which the contact problem only uses inside a defect
// correction checked against the exact velocities (core/step/contact_problem.h). A tree whose rows
// changed gets its part built from this step's factorization: exact. So a contact that appears on
// one body costs the rebuild of its tree's part, not of the whole matrix.
#pragma once

#include "core/contact.h"
#include "core/delassus.h"
#include "core/impulse_solver.h"
#include "core/step/row_key.h"

#include <cstdint>
#include <span>
#include <vector>

namespace frontier::core
{

class DelassusCache
{
  public:
    DelassusCache(const FrontierLayout& layout, ImpulseSolver& solver) : mLayout(layout), mSolver(solver) {}

    // A step's rows (laid out by layoutExtraRows; contacts for their keys): G's parts and islands,
    // no values yet. The last step's parts wait to be kept by prepare().
    void layOut(const std::vector<ExtraBlock>& blocks, const std::vector<Contact>& contacts);

    // Values for the parts of the flagged islands (one flag per island of matrix(); empty: all):
    // kept from the last step's part of the same tree when its rows match and `reuse`, else built
    // from the current factorization. Parts that already have values are left as they are.
    void prepare(std::span<const std::uint8_t> islands, bool reuse);
    // Builds again, from the current factorization, the parts of the flagged islands that were kept.
    void rebuild(std::span<const std::uint8_t> islands);
    // True when every part of the island was built this step (its G is exact).
    bool exact(int island) const;
    // Some part was built this step.
    bool builtAny() const { return mBuiltAny; }
    // True when every part has values (after prepare() of every island).
    bool complete() const;

    const DelassusMatrix& matrix() const { return mMemory.g; }

  private:
    enum class PartState : std::uint8_t
    {
        Empty, // no values yet this step
        Kept,  // the values of a recent step's part (G~)
        Built, // built this step (exact)
    };
    struct Record // what a part's values were built for
    {
        std::vector<RowKey> keys; // its blocks' keys, in the part's order
        long builtStep = -1;      // the step it was built in, -1: no values
    };

  public:
    // What carries over from one step to the next (core/step_memory.h), kept in one member: a
    // field added here is saved and restored with the rest.
    struct Memory
    {
        DelassusMatrix g, last; // this step's, the last step's
        std::vector<Record> records, lastRecords;
        std::vector<PartState> state;
        std::vector<RowKey> keys; // this step's, per block
        long step = 0;            // layOut() calls
    };
    const Memory& memory() const { return mMemory; }
    void restore(const Memory& memory);

  private:
    bool keep(int part);
    void build(std::span<const int> parts);
    bool flagged(std::span<const std::uint8_t> islands, int part) const;

    static constexpr int cMaxAge = 50;             // steps a part may stand in for the current one
    static constexpr double cReuseDistance = 1e-3; // m: how far a contact may move
    static constexpr double cReuseTurn = 0.999;    // the cosine a contact's normal may turn by

    const FrontierLayout& mLayout;
    ImpulseSolver& mSolver;
    Memory mMemory;
    const std::vector<ExtraBlock>* mBlocks = nullptr; // this step's (the caller's, stable through the step)
    std::vector<int> mToBuild;                        // scratch
    bool mBuiltAny = false;
};

} // namespace frontier::core
