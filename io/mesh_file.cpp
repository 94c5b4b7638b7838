// io/mesh_file.cpp: mesh files through assimp, flattened into one triangle list in the shape frame.
#include "io/mesh_file.h"

#include "core/interrupt.h"
#include "io/file_util.h"
#include "io/scene.h"
#include "io/xml_scan.h"

#include <algorithm>
#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/ProgressHandler.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <cctype>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sys/stat.h>
#include <thread>
#include <unordered_map>
#include <utility>

namespace frontier::io::detail
{

namespace
{

// What a mesh file may expand to (scenes/README.md "Meshes"): a file a few KB long can instance
// its nodes into billions (COLLADA <instance_node>), or nest them deeper than a reader's recursion.
constexpr std::size_t cMaxNodeDepth = 256;         // levels of nodes, instances included
constexpr std::size_t cMaxNodes = 100000;          // nodes, every instance counted
constexpr std::size_t cMaxVertices = 30000000;     // vertices of all mesh instances (before merging)
constexpr std::size_t cMaxTriangles = 30000000;    // faces of all mesh instances
constexpr std::size_t cCheckpointVertices = 65536; // vertices collected between interrupt checks

// A COLLADA file's <node> elements as written: their nesting and <instance_node> references.
class ColladaNodes
{
  public:
    ColladaNodes(const std::string& path, const std::string& text) : mPath(path), mText(text)
    {
        XmlDepthCheck depth(path, text, "a COLLADA file needs a few dozen");
        scanXmlTags(path, text, "COLLADA file", "the <COLLADA> element",
                    [&](const XmlTag& tag)
                    {
                        depth.visit(tag);
                        visit(tag);
                    });
    }

    // Throws InputError at the node (or <instance_node>) where the node tree that the visual
    // scenes instance goes beyond cMaxNodeDepth levels or cMaxNodes nodes, or instances itself.
    void checkExpansion()
    {
        std::map<std::string, std::vector<std::size_t>> named; // id and name -> nodes
        for (std::size_t n = 0; n < mNodes.size(); ++n)
        {
            for (const std::string* key : {&mNodes[n].id, &mNodes[n].name})
            {
                if (!key->empty())
                {
                    named[*key].push_back(n);
                }
            }
        }
        // Assimp resolves a reference by id in <library_nodes>, else by id or name in the scene:
        // every node of that id or name is counted as instanced (an upper bound).
        std::size_t instances = 0;
        for (Node& node : mNodes)
        {
            for (const auto& [target, at] : node.references)
            {
                if (const auto it = named.find(target); it != named.end())
                {
                    instances += it->second.size();
                    if (instances > cMaxNodes)
                    {
                        fail(at, "more than " + std::to_string(cMaxNodes) +
                                     " node instances (<instance_node>), the limit for a mesh file");
                    }
                    for (const std::size_t t : it->second)
                    {
                        node.edges.emplace_back(t, at);
                    }
                }
            }
        }
        std::size_t total = 0;
        for (std::size_t n = 0; n < mNodes.size(); ++n)
        {
            if (mNodes[n].inScene && mNodes[n].parent < 0)
            {
                expand(n);
                total += mNodes[n].count;
                if (total > cMaxNodes)
                {
                    fail(mNodes[n].offset, "the visual scene expands to more than " +
                                               std::to_string(cMaxNodes) +
                                               " nodes (instances counted), the limit for a mesh file");
                }
            }
        }
    }

  private:
    struct Node
    {
        long parent = -1; // the enclosing <node>
        std::size_t offset = 0;
        bool inScene = false; // inside a <visual_scene>
        std::string id, name;
        std::vector<std::pair<std::string, std::size_t>> references; // <instance_node> target, offset
        std::vector<std::pair<std::size_t, std::size_t>> edges; // child or instance, offset of the reference
        // Once expanded: 0 unvisited, 1 on the walk's path, 2 done; nodes (itself included) and levels.
        int state = 0;
        std::size_t count = 0;
        std::size_t depth = 0;
    };

    void visit(const XmlTag& tag)
    {
        if (tag.end)
        {
            if (!mOpen.empty())
            {
                if (mOpen.back() == "node" && !mNodeStack.empty())
                {
                    mNodeStack.pop_back();
                }
                mScenes -= mOpen.back() == "visual_scene" ? 1 : 0;
                mOpen.pop_back();
            }
            return;
        }
        if (tag.name == "node")
        {
            if (mNodes.size() >= cMaxNodes)
            {
                fail(tag.offset,
                     "more than " + std::to_string(cMaxNodes) + " nodes, the limit for a mesh file");
            }
            if (mNodeStack.size() >= cMaxNodeDepth)
            {
                fail(tag.offset, "nodes nested more than " + std::to_string(cMaxNodeDepth) +
                                     " levels deep, the limit for a mesh file");
            }
            Node node;
            node.parent = mNodeStack.empty() ? -1 : static_cast<long>(mNodeStack.back());
            node.offset = tag.offset;
            node.inScene = mScenes > 0;
            node.id = xmlAttribute(tag.attributes, "id").value_or("");
            node.name = xmlAttribute(tag.attributes, "name").value_or("");
            if (node.parent >= 0)
            {
                mNodes[static_cast<std::size_t>(node.parent)].edges.emplace_back(mNodes.size(), tag.offset);
            }
            mNodes.push_back(std::move(node));
            if (!tag.empty)
            {
                mNodeStack.push_back(mNodes.size() - 1);
            }
        }
        else if (tag.name == "instance_node" && !mNodeStack.empty())
        {
            const std::string url = xmlAttribute(tag.attributes, "url").value_or("");
            if (url.starts_with("#"))
            {
                mNodes[mNodeStack.back()].references.emplace_back(url.substr(1), tag.offset);
            }
        }
        if (!tag.empty)
        {
            mScenes += tag.name == "visual_scene" ? 1 : 0;
            mOpen.push_back(tag.name);
        }
    }

    // Counts and levels below `root`, depth first without recursion (the references may chain
    // nodes far deeper than the nesting).
    void expand(std::size_t root)
    {
        std::vector<std::pair<std::size_t, std::size_t>> path{{root, 0}}; // node, next edge
        mNodes[root].state = 1;
        while (!path.empty())
        {
            auto& [n, next] = path.back();
            Node& node = mNodes[n];
            if (node.state == 2)
            {
                path.pop_back();
                continue;
            }
            if (next < node.edges.size())
            {
                const auto [child, at] = node.edges[next++];
                Node& c = mNodes[child];
                if (c.state == 1)
                {
                    fail(at, "<instance_node> instances a node that contains it (a node may not instance "
                             "itself or its ancestors)");
                }
                if (c.state == 0)
                {
                    c.state = 1;
                    path.emplace_back(child, 0);
                }
                continue;
            }
            node.count = 1;
            node.depth = 1;
            for (const auto& [child, at] : node.edges)
            {
                node.count = std::min(node.count + mNodes[child].count, cMaxNodes + 1);
                node.depth = std::max(node.depth, mNodes[child].depth + 1);
            }
            if (node.depth > cMaxNodeDepth)
            {
                fail(node.offset, "this node holds nodes (instances included) more than " +
                                      std::to_string(cMaxNodeDepth) +
                                      " levels deep, the limit for a mesh file");
            }
            if (node.count > cMaxNodes)
            {
                fail(node.offset, "this node expands to more than " + std::to_string(cMaxNodes) +
                                      " nodes (instances counted), the limit for a mesh file");
            }
            node.state = 2;
            path.pop_back();
        }
    }

    [[noreturn]] void fail(std::size_t offset, const std::string& message) const
    {
        const TextPosition at = positionOf(mText, offset);
        throw InputError(mPath, at.line, at.column, message);
    }

    const std::string& mPath;
    const std::string& mText;
    std::vector<Node> mNodes;
    std::vector<std::size_t> mNodeStack; // the open <node> elements
    std::vector<std::string_view> mOpen; // the open elements
    int mScenes = 0;                     // open <visual_scene> elements
};

// Whether assimp would read `path` as COLLADA: by its extension, or "<COLLADA" near its start.
bool isCollada(const std::string& path, const std::string& head)
{
    if (lowerExtension(path) == ".dae")
    {
        return true;
    }
    std::string lower = head;
    for (char& c : lower)
    {
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    return lower.find("<collada") != std::string::npos;
}

// The first `bytes` bytes of the file (fewer when it is shorter).
std::string fileHead(const std::string& path, std::size_t bytes)
{
    std::ifstream in(path, std::ios::binary);
    std::string head(bytes, '\0');
    in.read(head.data(), static_cast<std::streamsize>(bytes));
    head.resize(static_cast<std::size_t>(std::max<std::streamsize>(0, in.gcount())));
    return head;
}

// Refuses, before assimp reads it, a zip archive (a .zae holds COLLADA that no check here would
// see) and a COLLADA file whose nodes nest or instance beyond the limits.
void checkBeforeReading(const std::string& path)
{
    const std::string head = fileHead(path, 4096);
    if (head.starts_with("PK\x03\x04") || lowerExtension(path) == ".zae")
    {
        throw InputError(path, 0, 0,
                         "mesh file is a zip archive (.zae, .3mf, ...), which is not read; extract the mesh "
                         "file from it");
    }
    if (isCollada(path, head))
    {
        const std::string text = readTextFile(path, "mesh file");
        ColladaNodes(path, text).checkExpansion();
    }
}

// Throws InputError(path, 0, 0, ...) when the scene assimp returned goes beyond the limits:
// nodes and their depth (any format), vertices and faces of every mesh instance.
void checkExpandedSize(const std::string& path, const aiScene& scene)
{
    std::size_t nodes = 0, vertices = 0, faces = 0;
    std::vector<std::pair<const aiNode*, std::size_t>> pending{{scene.mRootNode, 1}}; // node, level
    while (!pending.empty())
    {
        const auto [node, level] = pending.back();
        pending.pop_back();
        if (++nodes > cMaxNodes || level > cMaxNodeDepth)
        {
            throw InputError(path, 0, 0,
                             "mesh file has more than " +
                                 (level > cMaxNodeDepth ? std::to_string(cMaxNodeDepth) + " levels of nodes"
                                                        : std::to_string(cMaxNodes) + " nodes") +
                                 ", the limit for a mesh file");
        }
        for (unsigned i = 0; i < node->mNumMeshes; ++i)
        {
            if (node->mMeshes[i] >= scene.mNumMeshes)
            {
                throw InputError(path, 0, 0, "mesh file has a node naming a mesh that does not exist");
            }
            vertices += scene.mMeshes[node->mMeshes[i]]->mNumVertices;
            faces += scene.mMeshes[node->mMeshes[i]]->mNumFaces;
        }
        if (vertices > cMaxVertices || faces > cMaxTriangles)
        {
            throw InputError(path, 0, 0,
                             "mesh file expands to more than " +
                                 (vertices > cMaxVertices ? std::to_string(cMaxVertices) + " vertices"
                                                          : std::to_string(cMaxTriangles) + " faces") +
                                 " (every instance of its meshes counted), the limit for a mesh file");
        }
        for (unsigned i = 0; i < node->mNumChildren; ++i)
        {
            pending.emplace_back(node->mChildren[i], level + 1);
        }
    }
}

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
            if (v % cCheckpointVertices == 0)
            {
                core::throwIfInterrupted();
            }
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
        mOpened.emplace_back(file);
        return Assimp::DefaultIOSystem::Open(file, mode);
    }

    const std::optional<InputError>& refused() const { return mRefused; }
    // The files opened, in order (the mesh file itself included).
    const std::vector<std::string>& opened() const { return mOpened; }

  private:
    std::optional<InputError> mRefused;
    std::vector<std::string> mOpened;
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

// Stops assimp between its steps once a signal has come (core/interrupt.h).
class InterruptCheck final : public Assimp::ProgressHandler
{
  public:
    bool Update(float) override { return core::interruptSignal() == 0; }
};

// Assimp reading `path` on a thread of its own: its readers have no checkpoint inside (a binary
// STL of millions of triangles is one call), so the caller waits for it, checking for a signal
// every 50 ms, and leaves it behind (to end with the process) when one comes.
class BackgroundImport
{
  public:
    explicit BackgroundImport(const std::string& path) : mState(std::make_shared<State>())
    {
        auto* io = new CheckedIOSystem; // the importer owns it
        mState->io = io;
        mState->importer.SetIOHandler(io);
        mState->importer.SetProgressHandler(new InterruptCheck); // the importer owns it
        // Robot files give a link's COLLADA and STL meshes in the same frame: a COLLADA file's
        // coordinates are used as written, whatever its <up_axis>, not rotated into y-up.
        mState->importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
        mState->importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                                            aiPrimitiveType_POINT | aiPrimitiveType_LINE);
        std::thread(
            [state = mState, path]
            {
                // No aiProcess_JoinIdenticalVertices: it keeps apart corners whose normals differ
                // (every STL corner) and took 2 s per million triangles; MeshCollector merges
                // positions exactly instead.
                const aiScene* scene = nullptr;
                std::exception_ptr failure;
                try
                {
                    scene = state->importer.ReadFile(path, aiProcess_Triangulate | aiProcess_SortByPType |
                                                               aiProcess_ValidateDataStructure);
                }
                catch (...)
                {
                    failure = std::current_exception(); // out of memory
                }
                const std::lock_guard lock(state->mutex);
                state->scene = scene;
                state->failure = failure;
                state->done = true;
                state->finished.notify_all();
            })
            .detach();
    }

    // The scene assimp returned (null: see importer().GetErrorString()); throws core::Interrupted
    // when a signal comes first.
    const aiScene* wait()
    {
        std::unique_lock lock(mState->mutex);
        while (!mState->finished.wait_for(lock, std::chrono::milliseconds(50), [&] { return mState->done; }))
        {
            core::throwIfInterrupted();
        }
        core::throwIfInterrupted();
        if (mState->failure)
        {
            std::rethrow_exception(mState->failure);
        }
        // The files assimp opened on its thread are this thread's inputs (InputFileLog).
        for (const std::string& file : mState->io->opened())
        {
            checkInputFile(file, "file named in a mesh file");
        }
        return mState->scene;
    }

    const Assimp::Importer& importer() const { return mState->importer; }
    const CheckedIOSystem& io() const { return *mState->io; }

  private:
    struct State
    {
        Assimp::Importer importer;
        CheckedIOSystem* io = nullptr;
        std::mutex mutex;
        std::condition_variable finished;
        bool done = false;
        const aiScene* scene = nullptr;
        std::exception_ptr failure;
    };
    std::shared_ptr<State> mState; // shared with the thread, which may outlive this
};

} // namespace

core::Shape loadMeshFile(const std::string& path, const core::Vec3& scale)
{
    // Assimp is handed only a regular file of bounded size (io/file_util.h): it would wait forever
    // on a FIFO and read /dev/zero until memory runs out; nor a file that would expand beyond the
    // limits while it reads (checkBeforeReading).
    checkInputFile(path, "mesh file");
    checkBeforeReading(path);
    BackgroundImport import(path);
    const aiScene* scene = import.wait();
    const CheckedIOSystem* io = &import.io();
    const Assimp::Importer& importer = import.importer();
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
        checkExpandedSize(path, *scene);
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
