// io/mesh_file.cpp: Wavefront .obj (v and f lines) and STL (ASCII or binary) readers.
#include "io/mesh_file.h"

#include "io/file_util.h"
#include "io/scene.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <string_view>

namespace frontier::io::detail
{

namespace
{

struct Token
{
    std::string_view text;
    int column = 0; // 1-based
};

std::vector<Token> splitLine(std::string_view line)
{
    std::vector<Token> out;
    std::size_t i = 0;
    while (i < line.size())
    {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r'))
        {
            ++i;
        }
        const std::size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r')
        {
            ++i;
        }
        if (i > start)
        {
            out.push_back({line.substr(start, i - start), static_cast<int>(start) + 1});
        }
    }
    return out;
}

class LineReader
{
  public:
    explicit LineReader(const std::string& text) : mText(text) {}
    bool next(std::string_view& line)
    {
        if (mPos >= mText.size())
        {
            return false;
        }
        const std::size_t end = mText.find('\n', mPos);
        const std::size_t stop = end == std::string::npos ? mText.size() : end;
        line = std::string_view(mText).substr(mPos, stop - mPos);
        mPos = stop + 1;
        ++mLine;
        return true;
    }
    int line() const { return mLine; }

  private:
    const std::string& mText;
    std::size_t mPos = 0;
    int mLine = 0;
};

double parseNumber(const std::string& path, int line, const Token& token, const char* what)
{
    double value = 0.0;
    const char* begin = token.text.data();
    const char* end = begin + token.text.size();
    if (*begin == '+')
    {
        ++begin;
    }
    const auto result = std::from_chars(begin, end, value);
    if (result.ec != std::errc() || result.ptr != end || !std::isfinite(value))
    {
        throw InputError(path, line, token.column,
                         std::string("expected a finite number for ") + what + ", got '" +
                             std::string(token.text) + "'");
    }
    return value;
}

core::Shape loadObj(const std::string& path, const std::string& text)
{
    core::Shape shape;
    shape.type = core::ShapeType::Mesh;
    LineReader reader(text);
    std::string_view line;
    while (reader.next(line))
    {
        const std::size_t hash = line.find('#');
        const std::vector<Token> tokens = splitLine(line.substr(0, hash));
        if (tokens.empty())
        {
            continue;
        }
        if (tokens[0].text == "v")
        {
            if (tokens.size() < 4)
            {
                throw InputError(path, reader.line(), tokens[0].column,
                                 "expected 'v x y z' (3 coordinates), got " +
                                     std::to_string(tokens.size() - 1));
            }
            shape.vertices.emplace_back(parseNumber(path, reader.line(), tokens[1], "vertex x"),
                                        parseNumber(path, reader.line(), tokens[2], "vertex y"),
                                        parseNumber(path, reader.line(), tokens[3], "vertex z"));
        }
        else if (tokens[0].text == "f")
        {
            if (tokens.size() < 4)
            {
                throw InputError(path, reader.line(), tokens[0].column,
                                 "expected a face with at least 3 vertices, got " +
                                     std::to_string(tokens.size() - 1));
            }
            std::vector<int> face;
            for (std::size_t i = 1; i < tokens.size(); ++i)
            {
                // "i", "i/t", "i//n" or "i/t/n": the vertex index is before the first slash.
                const std::string_view field = tokens[i].text.substr(0, tokens[i].text.find('/'));
                long index = 0;
                const auto result = std::from_chars(field.data(), field.data() + field.size(), index);
                if (result.ec != std::errc() || result.ptr != field.data() + field.size() || index == 0)
                {
                    throw InputError(path, reader.line(), tokens[i].column,
                                     "expected a vertex index (1-based, or negative from the end), got '" +
                                         std::string(tokens[i].text) + "'");
                }
                const long count = static_cast<long>(shape.vertices.size());
                const long resolved = index > 0 ? index - 1 : count + index;
                if (resolved < 0 || resolved >= count)
                {
                    throw InputError(path, reader.line(), tokens[i].column,
                                     "vertex index " + std::to_string(index) + " is out of range (" +
                                         std::to_string(count) + " vertices defined so far)");
                }
                face.push_back(static_cast<int>(resolved));
            }
            for (std::size_t i = 1; i + 1 < face.size(); ++i)
            {
                shape.triangles.push_back({face[0], face[i], face[i + 1]});
            }
        }
        // Other statements (vn, vt, o, g, s, usemtl, mtllib, l, ...) do not affect the geometry.
    }
    return shape;
}

// Identical vertices (exact coordinates) become one, so the mesh is connected.
class VertexMerger
{
  public:
    explicit VertexMerger(core::Shape& shape) : mShape(shape) {}
    int add(const core::Vec3& v)
    {
        const auto [it, inserted] =
            mIndex.try_emplace({v.x(), v.y(), v.z()}, static_cast<int>(mShape.vertices.size()));
        if (inserted)
        {
            mShape.vertices.push_back(v);
        }
        return it->second;
    }

  private:
    core::Shape& mShape;
    std::map<std::array<double, 3>, int> mIndex;
};

core::Shape loadAsciiStl(const std::string& path, const std::string& text)
{
    core::Shape shape;
    shape.type = core::ShapeType::Mesh;
    VertexMerger merger(shape);
    LineReader reader(text);
    std::string_view line;
    std::vector<int> facet;
    bool inFacet = false;
    int facetLine = 0;
    while (reader.next(line))
    {
        const std::vector<Token> tokens = splitLine(line);
        if (tokens.empty())
        {
            continue;
        }
        const std::string_view word = tokens[0].text;
        if (word == "facet")
        {
            inFacet = true;
            facetLine = reader.line();
            facet.clear();
        }
        else if (word == "vertex")
        {
            if (!inFacet || tokens.size() != 4)
            {
                throw InputError(path, reader.line(), tokens[0].column,
                                 inFacet ? "expected 'vertex x y z'" : "'vertex' outside a 'facet'");
            }
            facet.push_back(merger.add({parseNumber(path, reader.line(), tokens[1], "vertex x"),
                                        parseNumber(path, reader.line(), tokens[2], "vertex y"),
                                        parseNumber(path, reader.line(), tokens[3], "vertex z")}));
        }
        else if (word == "endfacet")
        {
            if (!inFacet || facet.size() != 3)
            {
                throw InputError(path, facetLine, 1,
                                 "expected a facet with 3 vertices, got " + std::to_string(facet.size()));
            }
            shape.triangles.push_back({facet[0], facet[1], facet[2]});
            inFacet = false;
        }
        else if (word != "solid" && word != "endsolid" && word != "outer" && word != "endloop")
        {
            throw InputError(path, reader.line(), tokens[0].column,
                             "expected an ASCII STL keyword (solid, facet, outer loop, vertex, endloop, "
                             "endfacet, endsolid), got '" +
                                 std::string(word) + "'");
        }
    }
    if (inFacet)
    {
        throw InputError(path, facetLine, 1, "facet without 'endfacet'");
    }
    return shape;
}

core::Shape loadBinaryStl(const std::string& path, const std::string& data)
{
    constexpr std::size_t cHeader = 84;
    constexpr std::size_t cRecord = 50; // normal, 3 vertices (12 floats), 2 attribute bytes
    if (data.size() < cHeader)
    {
        throw InputError(path, 0, 0,
                         "expected a binary STL (84-byte header), got " + std::to_string(data.size()) +
                             " bytes");
    }
    std::uint32_t count = 0;
    std::memcpy(&count, data.data() + 80, sizeof(count)); // little-endian on the supported platforms
    if (data.size() != cHeader + cRecord * count)
    {
        throw InputError(path, 0, 0,
                         "binary STL declares " + std::to_string(count) + " triangles, expected " +
                             std::to_string(cHeader + cRecord * count) + " bytes, got " +
                             std::to_string(data.size()));
    }
    core::Shape shape;
    shape.type = core::ShapeType::Mesh;
    VertexMerger merger(shape);
    for (std::uint32_t t = 0; t < count; ++t)
    {
        float values[12];
        std::memcpy(values, data.data() + cHeader + cRecord * t, sizeof(values));
        std::array<int, 3> tri{};
        for (int k = 0; k < 3; ++k)
        {
            const core::Vec3 v(values[3 + 3 * k], values[4 + 3 * k], values[5 + 3 * k]);
            if (!v.allFinite())
            {
                throw InputError(path, 0, 0,
                                 "triangle " + std::to_string(t + 1) + " has a non-finite vertex");
            }
            tri[static_cast<std::size_t>(k)] = merger.add(v);
        }
        shape.triangles.push_back(tri);
    }
    return shape;
}

} // namespace

core::Shape loadMeshFile(const std::string& path, const core::Vec3& scale)
{
    const std::string ext = lowerExtension(path);
    if (ext != ".obj" && ext != ".stl")
    {
        throw InputError(path, 0, 0, "unsupported mesh format '" + ext + "'; expected .obj or .stl");
    }
    const std::string text = readTextFile(path);
    core::Shape shape;
    if (ext == ".obj")
    {
        shape = loadObj(path, text);
    }
    else if (text.starts_with("solid") && text.find('\0') == std::string::npos)
    {
        shape = loadAsciiStl(path, text);
    }
    else
    {
        shape = loadBinaryStl(path, text);
    }
    if (shape.triangles.empty())
    {
        throw InputError(path, 0, 0, "mesh has no triangles");
    }
    for (core::Vec3& v : shape.vertices)
    {
        v = v.cwiseProduct(scale);
    }
    shape.meshFile = path;
    return shape;
}

} // namespace frontier::io::detail
