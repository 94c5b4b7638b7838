// io/yaml_tree.cpp: the compact YAML tree and its builder on yaml-cpp's events.
#include "io/yaml_tree.h"

#include "io/scene.h"

#include <istream>
#include <limits>
#include <stdexcept>
#include <streambuf>
#include <unordered_map>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/parser.h>

namespace frontier::io::detail
{

namespace
{
const std::string cEmpty;
} // namespace

bool YamlNode::isNull() const
{
    return mTree == nullptr || mTree->node(mIndex).kind == YamlTree::Kind::Null;
}

bool YamlNode::isScalar() const
{
    return mTree != nullptr && mTree->node(mIndex).kind == YamlTree::Kind::Scalar;
}

bool YamlNode::isSequence() const
{
    return mTree != nullptr && mTree->node(mIndex).kind == YamlTree::Kind::Sequence;
}

bool YamlNode::isMap() const
{
    return mTree != nullptr && mTree->node(mIndex).kind == YamlTree::Kind::Map;
}

std::size_t YamlNode::size() const
{
    if (mTree == nullptr)
    {
        return 0;
    }
    const YamlTree::Node& n = mTree->node(mIndex);
    return n.kind == YamlTree::Kind::Map ? n.count / 2 : n.kind == YamlTree::Kind::Sequence ? n.count : 0;
}

YamlNode YamlNode::operator[](std::size_t i) const
{
    const YamlTree::Node& n = mTree->node(mIndex);
    if (n.kind != YamlTree::Kind::Sequence || n.itemByItem || i >= n.count)
    {
        throw std::logic_error("YamlNode: no sequence item " + std::to_string(i));
    }
    return YamlNode(mTree, mTree->mChildren[n.first + i]);
}

YamlNode YamlNode::key(std::size_t i) const
{
    const YamlTree::Node& n = mTree->node(mIndex);
    if (n.kind != YamlTree::Kind::Map || 2 * i >= n.count)
    {
        throw std::logic_error("YamlNode: no map pair " + std::to_string(i));
    }
    return YamlNode(mTree, mTree->mChildren[n.first + 2 * i]);
}

YamlNode YamlNode::value(std::size_t i) const
{
    const YamlTree::Node& n = mTree->node(mIndex);
    if (n.kind != YamlTree::Kind::Map || 2 * i >= n.count)
    {
        throw std::logic_error("YamlNode: no map pair " + std::to_string(i));
    }
    return YamlNode(mTree, mTree->mChildren[n.first + 2 * i + 1]);
}

const std::string& YamlNode::scalar() const
{
    return mTree != nullptr ? mTree->node(mIndex).scalar : cEmpty;
}

const std::string& YamlNode::tag() const
{
    return mTree != nullptr ? mTree->mTags[mTree->node(mIndex).tag] : cEmpty;
}

YAML::Mark YamlNode::mark() const
{
    return mTree != nullptr ? mTree->node(mIndex).mark : YAML::Mark::null_mark();
}

bool YamlNode::itemByItem() const
{
    return mTree != nullptr && mTree->node(mIndex).itemByItem;
}

YAML::EmitterStyle::value YamlNode::style() const
{
    return mTree != nullptr ? static_cast<YAML::EmitterStyle::value>(mTree->node(mIndex).style)
                            : YAML::EmitterStyle::Default;
}

// Builds YamlDocuments::first from the parser's events. Children are collected on one stack
// (mPending) while their collection is open and moved to the tree's child array, contiguous, when
// it closes. An item of a list taken by the YamlListHandler is handed over when complete and its
// nodes are dropped again, unless an anchor was defined inside it (a later alias may name it).
class YamlTreeBuilder final : public YAML::EventHandler
{
  public:
    YamlTreeBuilder(YamlDocuments& out, YamlListHandler* lists) : mOut(out), mTree(out.first), mLists(lists)
    {
        mTree.mTags.emplace_back(); // tag 0: none
        mAnchors.push_back(0);      // anchors count from 1
    }

    void OnDocumentStart(const YAML::Mark& mark) override
    {
        stuck = mOut.count > 0 && mark.pos == lastStart.pos;
        lastStart = mark;
        ++mOut.count;
    }
    void OnDocumentEnd() override {}

    void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override
    {
        if (!counting(mark))
        {
            const Context context = begin();
            end(add(mark, YamlTree::Kind::Null, cEmpty, anchor), context);
        }
    }
    void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override
    {
        if (!counting(mark))
        {
            if (anchor >= mAnchors.size() || anchor == YAML::NullAnchor)
            {
                throw std::logic_error("YAML alias of an anchor never defined");
            }
            const Context context = begin();
            end(mAnchors[anchor], context);
        }
    }
    void OnScalar(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                  const std::string& value) override
    {
        if (!counting(mark))
        {
            const Context context = begin();
            const std::uint32_t index = add(mark, YamlTree::Kind::Scalar, tag, anchor);
            mTree.mNodes[index].scalar = value;
            end(index, context);
        }
    }
    void OnSequenceStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                         YAML::EmitterStyle::value style) override
    {
        open(mark, YamlTree::Kind::Sequence, tag, anchor, style);
    }
    void OnSequenceEnd() override { close(); }
    void OnMapStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                    YAML::EmitterStyle::value style) override
    {
        open(mark, YamlTree::Kind::Map, tag, anchor, style);
    }
    void OnMapEnd() override { close(); }

    bool stuck = false; // a document started where the one before started: no progress
    YAML::Mark lastStart;

  private:
    // Where a node that begins now goes.
    struct Context
    {
        bool item = false;         // an item of a list taken item by item
        std::size_t itemNodes = 0; // ... the tree's sizes when it began
        std::size_t itemChildren = 0;
        std::size_t itemAnchors = 0; // ... anchors defined before it
        bool rootValue = false;      // the value of a key of the root map
        std::string key;             // ... that key
    };
    struct Open
    {
        std::uint32_t node = 0;
        std::size_t pending = 0; // its first child in mPending
        Context context;
        bool rootMap = false;    // the first document's root, a map
        bool itemByItem = false; // a list taken item by item
        std::string listKey;     // ... the root key it is the value of
        std::size_t items = 0;   // ... items handed over
    };

    // Documents after the first are counted, not built; the first node of the second is noted.
    bool counting(const YAML::Mark& mark)
    {
        if (mOut.count <= 1)
        {
            return false;
        }
        if (mOut.count == 2 && mOut.second.is_null())
        {
            mOut.second = mark;
        }
        return true;
    }

    Context begin()
    {
        Context context;
        if (mOpen.empty())
        {
            return context;
        }
        const Open& parent = mOpen.back();
        if (parent.itemByItem)
        {
            context.item = true;
            context.itemNodes = mTree.mNodes.size();
            context.itemChildren = mTree.mChildren.size();
            context.itemAnchors = mAnchorsDefined;
        }
        else if (parent.rootMap && (mPending.size() - parent.pending) % 2 == 1)
        {
            const YamlTree::Node& key = mTree.mNodes[mPending.back()];
            context.rootValue = true;
            context.key = key.kind == YamlTree::Kind::Scalar ? key.scalar : std::string();
            if (mLists != nullptr)
            {
                mLists->onRootValueBegin(context.key);
            }
        }
        return context;
    }

    std::uint32_t add(const YAML::Mark& mark, YamlTree::Kind kind, const std::string& tag,
                      YAML::anchor_t anchor)
    {
        if (mTree.mNodes.size() >= std::numeric_limits<std::uint32_t>::max())
        {
            throw std::length_error("YAML document too large");
        }
        const auto index = static_cast<std::uint32_t>(mTree.mNodes.size());
        YamlTree::Node& node = mTree.mNodes.emplace_back();
        node.mark = mark;
        node.kind = kind;
        node.tag = tagIndex(tag);
        if (anchor != YAML::NullAnchor)
        {
            if (anchor >= mAnchors.size())
            {
                mAnchors.resize(anchor + 1, 0);
            }
            mAnchors[anchor] = index;
            ++mAnchorsDefined;
        }
        return index;
    }

    std::uint32_t tagIndex(const std::string& tag)
    {
        for (std::size_t i = 0; i < mTree.mTags.size() && i < 4; ++i) // "", "?", "!" and one more
        {
            if (mTree.mTags[i] == tag)
            {
                return static_cast<std::uint32_t>(i);
            }
        }
        const auto [it, added] = mTagIndex.emplace(tag, static_cast<std::uint32_t>(mTree.mTags.size()));
        if (added)
        {
            mTree.mTags.push_back(tag);
        }
        return it->second;
    }

    void open(const YAML::Mark& mark, YamlTree::Kind kind, const std::string& tag, YAML::anchor_t anchor,
              YAML::EmitterStyle::value style)
    {
        if (counting(mark))
        {
            return;
        }
        Open open;
        open.context = begin();
        open.node = add(mark, kind, tag, anchor);
        open.pending = mPending.size();
        open.rootMap = kind == YamlTree::Kind::Map && mOpen.empty();
        mTree.mNodes[open.node].style = static_cast<std::uint8_t>(style);
        if (kind == YamlTree::Kind::Sequence && open.context.rootValue && mLists != nullptr &&
            mLists->takeItems(open.context.key))
        {
            open.itemByItem = true;
            open.listKey = open.context.key;
            mTree.mNodes[open.node].itemByItem = true;
        }
        mOpen.push_back(std::move(open));
    }

    void close()
    {
        if (mOut.count > 1)
        {
            return;
        }
        Open open = std::move(mOpen.back());
        mOpen.pop_back();
        YamlTree::Node& node = mTree.mNodes[open.node];
        if (open.itemByItem)
        {
            node.count = static_cast<std::uint32_t>(open.items);
        }
        else
        {
            node.first = static_cast<std::uint32_t>(mTree.mChildren.size());
            node.count = static_cast<std::uint32_t>(mPending.size() - open.pending);
            mTree.mChildren.insert(mTree.mChildren.end(),
                                   mPending.begin() + static_cast<std::ptrdiff_t>(open.pending),
                                   mPending.end());
            mPending.resize(open.pending);
        }
        end(open.node, open.context);
    }

    // The node `index` is complete: it goes to its collection, to the list handler, or is the root.
    void end(std::uint32_t index, const Context& context)
    {
        if (mOpen.empty())
        {
            mTree.mRoot = index;
            mTree.mHasRoot = true;
            return;
        }
        Open& parent = mOpen.back();
        if (parent.itemByItem)
        {
            mTree.mNodes[parent.node].count = static_cast<std::uint32_t>(++parent.items); // so far
            mLists->onItem(parent.listKey, parent.items - 1, YamlNode(&mTree, index));
            if (mAnchorsDefined == context.itemAnchors)
            {
                mTree.mNodes.resize(context.itemNodes);
                mTree.mChildren.resize(context.itemChildren);
            }
            return;
        }
        mPending.push_back(index);
        if (context.rootValue && mLists != nullptr)
        {
            mLists->onRootValueEnd(context.key, YamlNode(&mTree, index));
        }
    }

    YamlDocuments& mOut;
    YamlTree& mTree;
    YamlListHandler* mLists;
    std::vector<Open> mOpen;
    std::vector<std::uint32_t> mPending;
    std::vector<std::uint32_t> mAnchors; // anchor id -> node
    std::size_t mAnchorsDefined = 0;
    std::unordered_map<std::string, std::uint32_t> mTagIndex;
};

namespace
{
// The text as an input stream without a copy of it.
class TextBuffer final : public std::streambuf
{
  public:
    explicit TextBuffer(const std::string& text)
    {
        char* begin = const_cast<char*>(text.data()); // read only: the get area is never written
        setg(begin, begin, begin + text.size());
    }
};
} // namespace

void parseYaml(const std::string& text, const std::string& file, YamlDocuments& out, YamlListHandler* lists)
{
    TextBuffer buffer(text);
    std::istream in(&buffer);
    YAML::Parser parser(in);
    YamlTreeBuilder builder(out, lists);
    while (parser.HandleNextDocument(builder))
    {
        if (builder.stuck)
        {
            const YAML::Mark& at = builder.lastStart;
            const std::size_t pos = static_cast<std::size_t>(at.pos);
            const std::string token = pos < text.size() ? std::string(1, text[pos]) : std::string();
            throw InputError(file, at.line + 1, at.column + 1,
                             "invalid YAML: unexpected '" + token +
                                 "' here (outside any [...] or {...}, and not the start of a value)");
        }
    }
}

} // namespace frontier::io::detail
