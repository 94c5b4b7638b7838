// io/mesh_file.cpp: mesh files through assimp, flattened into one triangle list in the shape frame.
#include "io/mesh_file.h"

#include "io/file_util.h"
#include "io/scene.h"

#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <optional>
#include <sys/stat.h>
#include <unordered_map>
#include <utility>

namespace frontier::io::detail
{

namespace
{

// Exact coordinates, so that merging never moves a vertex.
struct VertexKey
{
    double x, y, z;
    bool operator==(const VertexKey&) const = default;
};

struct VertexKeyHash
{
    std::size_t operator()(const VertexKey& k) const
    {
        const std::hash<double> h;
        std::size_t seed = h(k.x);
        seed ^= h(k.y) + 0x9e3779b97f4a7c15ULL + (seed << 6) + (seed >> 2);
        seed ^= h(k.z) + 0x9e3779b97f4a7c15ULL + (seed << 6) + (seed >> 2);
        return seed;
    }
};

// Collects the triangles of every mesh instance in the node tree into one shape, vertices
// merged across meshes and instances (a part split over several meshes stays one closed surface).
class MeshCollector
{
  public:
    MeshCollector(const std::string& path, const core::Vec3& scale) : mPath(path), mScale(scale)
    {
        mShape.type = core::ShapeType::Mesh;
        mShape.meshFile = path;
    }

    void addScene(const aiScene& scene)
    {
        std::size_t corners = 0; // distinct vertices at most, when each mesh is used once
        for (unsigned i = 0; i < scene.mNumMeshes; ++i)
        {
            corners += scene.mMeshes[i]->mNumVertices;
        }
        mIndex.reserve(corners);
        // Depth-first with an explicit stack: a file's node tree may be deeper than the call stack.
        // Assimp 5.2 puts a COLLADA file's <unit meter> into the root node's transform (the
        // scene metadata has no unit for it), so the walk from the root applies the unit too.
        std::vector<std::pair<const aiNode*, Eigen::Affine3d>> pending;
        pending.emplace_back(scene.mRootNode, Eigen::Affine3d::Identity());
        while (!pending.empty())
        {
            const auto [node, parent_FP] = pending.back();
            pending.pop_back();
            const Eigen::Affine3d node_FN = parent_FP * toAffine(node->mTransformation);
            for (unsigned i = 0; i < node->mNumMeshes; ++i)
            {
                addMesh(*scene.mMeshes[node->mMeshes[i]], node_FN);
            }
            for (unsigned i = node->mNumChildren; i-- > 0;)
            {
                pending.emplace_back(node->mChildren[i], node_FN);
            }
        }
    }

    core::Shape take() { return std::move(mShape); }

  private:
    // aiMatrix4x4 is row-major: a1..a4 is the first row.
    static Eigen::Affine3d toAffine(const aiMatrix4x4& m)
    {
        Eigen::Matrix4d out;
        out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
        return Eigen::Affine3d(out);
    }

    void addMesh(const aiMesh& mesh, const Eigen::Affine3d& mesh_FM)
    {
        std::vector<int> index(mesh.mNumVertices);
        for (unsigned v = 0; v < mesh.mNumVertices; ++v)
        {
            const aiVector3D& p = mesh.mVertices[v];
            const core::Vec3 p_S = (mesh_FM * core::Vec3(p.x, p.y, p.z)).cwiseProduct(mScale);
            if (!p_S.allFinite())
            {
                throw InputError(mPath, 0, 0, "mesh has a non-finite vertex");
            }
            index[v] = addVertex(p_S);
        }
        // A mirroring node transform or scale (an odd number of negative components) turns the
        // surface inside out; swap two corners to undo it.
        const bool mirrored = mesh_FM.linear().determinant() * mScale.prod() < 0.0;
        for (unsigned f = 0; f < mesh.mNumFaces; ++f)
        {
            const aiFace& face = mesh.mFaces[f];
            if (face.mNumIndices != 3)
            {
                continue; // points and lines: no surface
            }
            std::array<int, 3> tri{};
            for (unsigned k = 0; k < 3; ++k)
            {
                if (face.mIndices[k] >= mesh.mNumVertices)
                {
                    throw InputError(mPath, 0, 0, "mesh has a face with a vertex index out of range");
                }
                tri[k] = index[face.mIndices[k]];
            }
            if (mirrored)
            {
                std::swap(tri[1], tri[2]);
            }
            mShape.triangles.push_back(tri);
        }
    }

    int addVertex(const core::Vec3& p)
    {
        const auto [it, inserted] =
            mIndex.try_emplace(VertexKey{p.x(), p.y(), p.z()}, static_cast<int>(mShape.vertices.size()));
        if (inserted)
        {
            mShape.vertices.push_back(p);
        }
        return it->second;
    }

    const std::string& mPath;
    core::Vec3 mScale;
    core::Shape mShape;
    std::unordered_map<VertexKey, int, VertexKeyHash> mIndex;
};

// Every file assimp opens (the mesh, an OBJ's mtllib, a glTF's buffers, ...) goes through
// checkInputFile (io/file_util.h) first: a FIFO or a device named inside a mesh file would block
// assimp or feed it without end. Assimp catches exceptions thrown inside its readers and reports
// "internal error", so a refusal is kept here and thrown after ReadFile returns.
class CheckedIOSystem final : public Assimp::DefaultIOSystem
{
  public:
    // stat() only: the default opens the file to see whether it exists, which blocks on a FIFO
    // until a writer comes.
    bool Exists(const char* file) const override
    {
        struct stat info
        {
        };
        return ::stat(file, &info) == 0;
    }

    Assimp::IOStream* Open(const char* file, const char* mode) override
    {
        if (!Exists(file))
        {
            return nullptr; // a missing material file: assimp goes on without it, as it always did
        }
        try
        {
            checkInputFile(file, "file named in a mesh file");
        }
        catch (const InputError& refused)
        {
            if (!mRefused)
            {
                mRefused = refused;
            }
            return nullptr;
        }
        return Assimp::DefaultIOSystem::Open(file, mode);
    }

    const std::optional<InputError>& refused() const { return mRefused; }

  private:
    std::optional<InputError> mRefused;
};

// The 1-based line of `path`'s text where `name` first appears after "mtllib" (0 when none).
int mtllibLine(const std::string& path, const std::string& name)
{
    const std::string text = readTextFile(path, "mesh file");
    const std::string base = name.substr(name.find_last_of('/') + 1);
    for (std::size_t at = text.find("mtllib"); at != std::string::npos; at = text.find("mtllib", at + 1))
    {
        const std::size_t end = text.find('\n', at);
        if (text.substr(at, end == std::string::npos ? std::string::npos : end - at).find(base) !=
            std::string::npos)
        {
            return positionOf(text, at).line;
        }
    }
    return 0;
}

} // namespace

core::Shape loadMeshFile(const std::string& path, const core::Vec3& scale)
{
    // Assimp is handed only a regular file of bounded size (io/file_util.h): it would wait forever
    // on a FIFO and read /dev/zero until memory runs out.
    checkInputFile(path, "mesh file");
    Assimp::Importer importer;
    auto* io = new CheckedIOSystem; // the importer owns it
    importer.SetIOHandler(io);
    // Robot files give a link's COLLADA and STL meshes in the same frame: a COLLADA file's
    // coordinates are used as written, whatever its <up_axis>, not rotated into y-up.
    importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    // No aiProcess_JoinIdenticalVertices: it keeps apart corners whose normals differ (every STL
    // corner) and took 2 s per million triangles; MeshCollector merges positions exactly instead.
    const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_SortByPType |
                                                       aiProcess_ValidateDataStructure);
    if (io->refused())
    {
        const InputError& refused = *io->refused();
        throw InputError(path, mtllibLine(path, refused.file()), 0,
                         "mesh file refers to '" + refused.file() + "': " + refused.message());
    }
    if (scene == nullptr)
    {
        throw InputError(path, 0, 0,
                         std::string("the mesh importer (assimp) failed: ") + importer.GetErrorString());
    }
    MeshCollector collector(path, scale);
    if (scene->mRootNode != nullptr && (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) == 0)
    {
        collector.addScene(*scene);
    }
    core::Shape shape = collector.take();
    if (shape.triangles.empty())
    {
        throw InputError(path, 0, 0, "mesh file has no triangles");
    }
    return shape;
}

} // namespace frontier::io::detail
