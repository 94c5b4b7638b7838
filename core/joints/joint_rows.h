// core/joints/joint_rows.h: a joint as rows of a Jacobian between two bodies (docs/method.md §2).
//
// Every joint k between body a (the joint's parent, possibly the world) and body b (its child)
// is r_k scalar velocity conditions
//     J_a u_a + J_b u_b = 0,        u = [v; w] (world frame: m/s, rad/s)
// and the joint impulse body a receives is J_a^T lambda, body b J_b^T lambda (N s, N m s).
// Each row is the exact time derivative of a position-level condition C(q) = 0, so the same
// rows drive the velocity solve and the drift correction; `error` holds C (m or rad).
// A joint's block may end with drive rows (core/joints/drive.h): compliant rows on its
// coordinates, J u + E lambda = c, with no position condition (error 0).
#pragma once

#include "core/large_vector.h"
#include "core/model.h"

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <stdexcept>

namespace frontier::core
{

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
// A joint's Jacobian blocks are stored row by row, so a joint of r rows occupies its first r x 6
// doubles contiguously: the O(n) factorization streams only the rows a joint has.
using JacobianRows = Eigen::Matrix<double, 6, 6, Eigen::RowMajor>;

struct JointRows
{
    int count = 0;          // rows of the joint's block, 3..6: its conditions, then its drive rows
    int constraintRows = 0; // rows 0..constraintRows-1 are the conditions C(q) = 0 (docs/method.md §2)
    int positionRows = 0;   // rows 0..positionRows-1 are positions (m), the rest angles (rad)
    JacobianRows J_a = JacobianRows::Zero(); // rows 0..count-1 used; zero for a world parent
    JacobianRows J_b = JacobianRows::Zero();
    Vec6 error = Vec6::Zero(); // C(q): position-level violation of each row (m or rad); 0 for drive rows
    // Drive rows (constraintRows..count-1): compliance E of J u + E lambda = c, (m/s)/(N s) or
    // (rad/s)/(N m s); entries of constraint rows are not read.
    Vec6 compliance = Vec6::Zero();
};

// One side's rows of a joint as a JointRowsTable keeps them: rows() rows of 6, row-major. Reads as
// a JacobianRows does (row, topRows, data).
class JacobianRowsRef
{
  public:
    JacobianRowsRef(const double* data, int rows) : mData(data), mRows(rows) {}
    Eigen::Map<const Eigen::Matrix<double, 1, 6>> row(int i) const
    {
        return Eigen::Map<const Eigen::Matrix<double, 1, 6>>(mData + 6 * i);
    }
    Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>> topRows(int n) const
    {
        return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>>(mData, n, 6);
    }
    const double* data() const { return mData; }
    int rows() const { return mRows; }

  private:
    const double* mData;
    int mRows;
};

// Joint k's rows as a RowSystem keeps them (JointRowsTable::operator[]): the members of a JointRows,
// read in place (J_a, J_b) or copied (error, compliance). J_a and J_b have the rows the joint's
// block can have (its conditions and drive rows); rows count..rows()-1 hold what an earlier
// assembly left there (assembleJointConditions rewrites the conditions only). Converts to the
// JointRows it was stored from (rows it does not have zero).
struct JointRowsView
{
    int count = 0;
    int constraintRows = 0;
    int positionRows = 0;
    JacobianRowsRef J_a{nullptr, 0};
    JacobianRowsRef J_b{nullptr, 0};
    Vec6 error = Vec6::Zero();      // zero beyond count
    Vec6 compliance = Vec6::Zero(); // of the drive rows; zero for condition rows

    operator JointRows() const; // NOLINT(google-explicit-constructor): RowSystem::joints[k] reads as before
};

// Joint k's room in a JointRowsTable (JointRowsTable::slot), which the row writers fill in place
// as they fill a JointRows: J_a and J_b with the rows the joint's block can have, its errors; the
// compliance of drive row r (only those are kept).
struct JointRowsSlot
{
    using RowsMap = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>>;
    struct DriveCompliance
    {
        double* values;
        int firstDrive;
        double& operator()(int r) const { return values[r - firstDrive]; }
    };
    int count = 0;
    int constraintRows = 0;
    int positionRows = 0;
    RowsMap J_a;
    RowsMap J_b;
    Eigen::Map<Eigen::VectorXd> error;
    DriveCompliance compliance;
};

// The rows of every joint of a system, each at the size its joint's block needs (a ball joint's 3
// rows take 39 doubles, where a JointRows holds 84), one joint after the other in one array.
class JointRowsTable
{
  public:
    // Joint k's rows where they are stored, for the loops that read every joint (the solver's).
    struct Rows
    {
        const double* J_a;        // capacity x 6, row-major
        const double* J_b;        // capacity x 6, row-major
        const double* error;      // count values
        const double* compliance; // compliance[r - firstDrive] for drive row r
        int count;
        int constraintRows;
        int positionRows;
        int capacity;
        int firstDrive; // capacity less the drive rows
    };

    std::size_t size() const { return mEntries.size(); }
    // Doubles it holds for all joints' rows.
    std::size_t storedValues() const { return mData.size(); }
    Rows rows(std::size_t k) const
    {
        const Entry& e = mEntries[k];
        const double* base = mData.data() + e.offset;
        const int cap = e.capacity;
        return {base + cap,       base + 7 * cap, base, base + 13 * cap,  e.count,
                e.constraintRows, e.positionRows, cap,  cap - e.driveRows};
    }
    JointRowsView operator[](std::size_t k) const
    {
        const Rows r = rows(k);
        JointRowsView view;
        view.count = r.count;
        view.constraintRows = r.constraintRows;
        view.positionRows = r.positionRows;
        view.J_a = JacobianRowsRef(r.J_a, r.capacity);
        view.J_b = JacobianRowsRef(r.J_b, r.capacity);
        for (int row = 0; row < r.count; ++row)
        {
            view.error(row) = r.error[row];
        }
        for (int row = r.firstDrive; row < r.capacity; ++row)
        {
            view.compliance(row) = r.compliance[row - r.firstDrive];
        }
        return view;
    }

    // Whether it was laid out for `joints` joints by a FrontierLayout of this id (0: none).
    bool laidOutFor(std::uint64_t layoutId, std::size_t joints) const
    {
        return layoutId != 0 && layoutId == mLayoutId && joints == mEntries.size();
    }
    // Room for joint k's capacity[k] rows, the last driveRows[k] of them drive rows, for a layout
    // (FrontierLayout::id, 0: none). Keeps what it holds when these are the sizes it has; else every
    // joint starts with no rows.
    void layOut(std::span<const std::uint8_t> capacity, std::span<const std::uint8_t> driveRows,
                std::uint64_t layoutId);
    // Joint k's room, for the row writers; then finish(k, slot) keeps its counts.
    JointRowsSlot slot(std::size_t k)
    {
        const Entry& e = mEntries[k];
        double* base = mData.data() + e.offset;
        const int cap = e.capacity;
        return {e.count,
                e.constraintRows,
                e.positionRows,
                JointRowsSlot::RowsMap(base + cap, cap, 6),
                JointRowsSlot::RowsMap(base + 7 * cap, cap, 6),
                Eigen::Map<Eigen::VectorXd>(base, cap),
                {base + 13 * cap, cap - e.driveRows}};
    }
    void finish(std::size_t k, const JointRowsSlot& slot)
    {
        Entry& e = mEntries[k];
        if (slot.count > e.capacity)
        {
            throw std::logic_error("joint rows: more rows than the joint's block has room for");
        }
        e.count = static_cast<std::uint8_t>(slot.count);
        e.constraintRows = static_cast<std::uint8_t>(slot.constraintRows);
        e.positionRows = static_cast<std::uint8_t>(slot.positionRows);
    }

  private:
    struct Entry
    {
        std::uint32_t offset = 0; // first double in mData: errors, J_a, J_b, compliances
        std::uint8_t capacity = 0;
        std::uint8_t driveRows = 0;
        std::uint8_t count = 0;
        std::uint8_t constraintRows = 0;
        std::uint8_t positionRows = 0;
    };
    LargeVector<Entry> mEntries;
    LargeVector<double> mData;
    std::uint64_t mLayoutId = 0;
};

// Pose of the two bodies of a joint. For a world parent, the parent pose is the identity; for a
// static parent, that body's fixed pose.
struct JointPose
{
    Vec3 x_a = Vec3::Zero(); // centre of mass of a (m)
    Quat q_a = Quat::Identity();
    Vec3 x_b = Vec3::Zero();
    Quat q_b = Quat::Identity();
};

// Fills the condition rows for the joint's type at the given pose (count = constraintRows; drive
// rows are appended by writeDriveRows, core/joints/drive.h). parentMoves: false for world/static
// parents (J_a is then left zero).
void evaluateJoint(const Joint& joint, const JointPose& pose, bool parentMoves, JointRows& out);

namespace detail
{
// Geometry shared by the per-type files, evaluated once per joint.
struct JointGeometry
{
    Mat3 R_a, R_b;
    Vec3 p_a, p_b; // anchors in world (m)
    Vec3 r_a, r_b; // p - x: lever arms from the centres of mass (m)
    Vec3 x_a;      // centre of mass of a (m)
    // Only C(q) is wanted (assembleJointConditions): writers may leave J_a and J_b as they were.
    bool conditionsOnly = false;
};
JointGeometry jointGeometry(const Joint& joint, const JointPose& pose);
// The same with the bodies' rotation matrices given (R_a: identity for a world parent), as
// pose.q_a.toRotationMatrix() and pose.q_b.toRotationMatrix() would give them.
JointGeometry jointGeometry(const Joint& joint, const JointPose& pose, const Mat3& R_a, const Mat3& R_b);

// Row writers, each appending at row `row` and returning the next free row. `Rows` is JointRows
// or JointRowsSlot (the same rows written in place into a JointRowsTable).
template <class Rows> int writeBallRows(const JointGeometry& g, Rows& out, int row);
template <class Rows>
int writeAxisAlignmentRows(const Joint& joint, const JointGeometry& g, Rows& out, int row);
template <class Rows> int writeSlidingRow(const Vec3& local, const JointGeometry& g, Rows& out, int row);
template <class Rows> int writeSlidingRows(const Joint& joint, const JointGeometry& g, Rows& out, int row);
template <class Rows>
int writeWeldRotationRows(const Joint& joint, const JointPose& pose, Rows& out, int row);
template <class Rows> int writeTwistRow(const Joint& joint, const JointGeometry& g, Rows& out, int row);

// Per type; g = jointGeometry(joint, pose).
template <class Rows>
void writeBallJoint(const Joint& joint, const JointPose& pose, const JointGeometry& g, Rows& out);
template <class Rows>
void writeRevoluteJoint(const Joint& joint, const JointPose& pose, const JointGeometry& g, Rows& out);
template <class Rows>
void writeAngleJoint(const Joint& joint, const JointPose& pose, const JointGeometry& g, Rows& out);
template <class Rows>
void writeCylindricalJoint(const Joint& joint, const JointPose& pose, const JointGeometry& g, Rows& out);
template <class Rows>
void writePrismaticJoint(const Joint& joint, const JointPose& pose, const JointGeometry& g, Rows& out);
template <class Rows>
void writeFixedJoint(const Joint& joint, const JointPose& pose, const JointGeometry& g, Rows& out);
template <class Rows>
void writePlanarJoint(const Joint& joint, const JointPose& pose, const JointGeometry& g, Rows& out);
} // namespace detail

// evaluateJoint with the joint's geometry at that pose at hand (detail::jointGeometry), which the
// drive rows reuse; into a JointRows or in place into a JointRowsTable (JointRowsSlot).
template <class Rows>
void evaluateJoint(const Joint& joint, const JointPose& pose, const detail::JointGeometry& g,
                   bool parentMoves, Rows& out);

} // namespace frontier::core
