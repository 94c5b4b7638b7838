// io/mujoco_util.h: MuJoCo's arrays as Eigen values and its objects as owning pointers, for the
// MJCF reader (io/mjcf_compile.h, io/mjcf_model.h) and the comparison with MuJoCo (bench/peers).
#pragma once

#include "core/model.h"

#include <memory>
#include <mujoco/mujoco.h>

namespace frontier::io::detail
{

inline core::Vec3 mujocoVec3(const mjtNum* v)
{
    return {v[0], v[1], v[2]};
}

// MuJoCo's 3x3 matrices are row-major.
inline core::Mat3 mujocoMat3(const mjtNum* m)
{
    return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(m);
}

struct MujocoModelDeleter
{
    void operator()(mjModel* model) const { mj_deleteModel(model); }
};
struct MujocoDataDeleter
{
    void operator()(mjData* data) const { mj_deleteData(data); }
};
struct MujocoVfsDeleter
{
    void operator()(mjVFS* vfs) const
    {
        mj_deleteVFS(vfs);
        delete vfs;
    }
};
using MujocoModel = std::unique_ptr<mjModel, MujocoModelDeleter>;
using MujocoData = std::unique_ptr<mjData, MujocoDataDeleter>;
using MujocoVfs = std::unique_ptr<mjVFS, MujocoVfsDeleter>;

} // namespace frontier::io::detail
