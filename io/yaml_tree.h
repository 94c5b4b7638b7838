// io/yaml_tree.h: YAML text as a compact tree of located nodes, built from yaml-cpp's event parser
// (YAML::Parser), for io/'s readers and the batch plan reader; not part of the installed API.
//
// Why not yaml-cpp's own YAML::Node tree: it costs about 13 KB per body of a scene of boxes (each
// node a memory holder, a node_ref and a node_data with its own containers), and YAML::Load holds
// the whole document at once. Here a node is 64 bytes (its mark, kind, tag and scalar; a
// collection's children sit in one array shared by the tree), and a reader may take the items of
// chosen top-level lists one at a time (YamlListHandler): a scene's `bodies:` and `joints:` are
// read item by item and never exist as a whole.
//
// The nodes are what YAML::Load makes of the same text, because they come from the same parser's
// events: a plain `null`, `~` or an empty value is a null node; a plain scalar has the tag "?", a
// quoted one "!"; marks are yaml-cpp's (0-based); an alias is its anchor's node (so its mark is the
// anchor's); a map keeps duplicate keys, in document order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>
#include <yaml-cpp/emitterstyle.h>
#include <yaml-cpp/mark.h>

namespace frontier::io::detail
{

class YamlTree;

// One node of a YamlTree, or no node (a missing key: isDefined() is false). A handle: cheap to copy,
// valid while its tree lives (an item given to YamlListHandler::onItem only during that call).
class YamlNode
{
  public:
    YamlNode() = default;

    bool isDefined() const { return mTree != nullptr; }
    bool isNull() const; // also true for no node
    bool isScalar() const;
    bool isSequence() const;
    bool isMap() const;
    // Items of a sequence (for a list read item by item: how many were read), pairs of a map, 0 otherwise.
    std::size_t size() const;
    // Item i of a sequence (i < size(); not of a list read item by item).
    YamlNode operator[](std::size_t i) const;
    // Key and value of pair i of a map (i < size()).
    YamlNode key(std::size_t i) const;
    YamlNode value(std::size_t i) const;
    // The text of a scalar ("" for other nodes).
    const std::string& scalar() const;
    // The tag as yaml-cpp's parser gives it: "?" for plain scalars and untagged collections, "!"
    // for quoted scalars, "" for null nodes, else the resolved tag ("tag:yaml.org,2002:float", "!n").
    const std::string& tag() const;
    // Where the node starts (0-based line and column); YAML::Mark::null_mark() for no node.
    YAML::Mark mark() const;
    // A list whose items went to a YamlListHandler one by one and were not kept.
    bool itemByItem() const;
    // The style a collection was written in (Flow for [...] and {...}, Block, Default otherwise).
    YAML::EmitterStyle::value style() const;
    // The same number for the same node of one tree (an alias and its anchor are one node).
    std::uint32_t id() const { return mIndex; }

  private:
    friend class YamlTree;
    friend class YamlTreeBuilder;
    YamlNode(const YamlTree* tree, std::uint32_t index) : mTree(tree), mIndex(index) {}
    const YamlTree* mTree = nullptr;
    std::uint32_t mIndex = 0;
};

// The first document of a YAML text (parseYaml builds it). Its nodes refer to it: it neither
// moves nor copies.
class YamlTree
{
  public:
    YamlTree() = default;
    YamlTree(const YamlTree&) = delete;
    YamlTree& operator=(const YamlTree&) = delete;

    // The document's root; no node when the text holds no document.
    YamlNode root() const { return mHasRoot ? YamlNode(this, mRoot) : YamlNode(); }
    // Nodes held (an alias is not a node of its own).
    std::size_t nodeCount() const { return mNodes.size(); }

  private:
    friend class YamlNode;
    friend class YamlTreeBuilder;
    enum class Kind : std::uint8_t
    {
        Null,
        Scalar,
        Sequence,
        Map,
    };
    struct Node
    {
        YAML::Mark mark;
        std::uint32_t tag = 0;   // index into mTags
        std::uint32_t first = 0; // collections: first child in mChildren (maps: key, value, key, ...)
        std::uint32_t count = 0; // collections: children in mChildren; a list read item by item: items
        Kind kind = Kind::Null;
        std::uint8_t style = YAML::EmitterStyle::Default; // a YAML::EmitterStyle::value
        bool itemByItem = false; // a list whose items went to a YamlListHandler: none kept
        std::string scalar;
    };
    static_assert(sizeof(Node) <= 64);
    const Node& node(std::uint32_t index) const { return mNodes[index]; }

    std::vector<Node> mNodes;
    std::vector<std::uint32_t> mChildren;
    std::vector<std::string> mTags;
    std::uint32_t mRoot = 0;
    bool mHasRoot = false;
};

// Receives the items of top-level lists of the first document one at a time, in document order,
// while it is parsed. Only lists that are the value of a key of the root map can be taken this way.
class YamlListHandler
{
  public:
    virtual ~YamlListHandler() = default;
    // The value of the root map's key `key` begins (a key that is not a scalar is given as "").
    virtual void onRootValueBegin(const std::string& key) = 0;
    // That value is a list: true to take its items by onItem (the list stays in the tree as an
    // empty sequence whose size() is the number of items), false to keep it in the tree.
    virtual bool takeItems(const std::string& key) = 0;
    // Item `index` (0-based) of a list taken by takeItems. Valid during the call only.
    virtual void onItem(const std::string& key, std::size_t index, const YamlNode& item) = 0;
    // That value is complete: `value` (in the tree, unless it is an item-by-item list).
    virtual void onRootValueEnd(const std::string& key, const YamlNode& value) = 0;
};

// The documents of a YAML text: the first one as a tree, the others counted.
struct YamlDocuments
{
    YamlTree first;
    int count = 0;                               // documents in the text
    YAML::Mark second = YAML::Mark::null_mark(); // where the second one's root starts
};

// Parses `text` (read in place, not copied) into `out`: its first document as a tree, the items of
// the lists `lists` takes handed to it instead. Throws YAML::ParserException for malformed text, and
// InputError (in `file`) at a token yaml-cpp cannot move past: on a stray flow token outside any
// flow collection (a line that starts with ',' at the top level) yaml-cpp 0.7 would return the same
// empty document forever.
void parseYaml(const std::string& text, const std::string& file, YamlDocuments& out,
               YamlListHandler* lists = nullptr);

} // namespace frontier::io::detail
