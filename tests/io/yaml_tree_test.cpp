// tests/io/yaml_tree_test.cpp: io/yaml_tree.h's tree says what yaml-cpp's own YAML::Load tree says
// of the same text (kinds, scalars, tags, marks, sizes, collection styles, shared nodes), and the
// items of a list taken item by item are not kept.
#include "io/yaml_tree.h"
#include "io_test_util.h"

#include <filesystem>
#include <gtest/gtest.h>
#include <map>
#include <yaml-cpp/yaml.h>

namespace frontier::io::test
{
namespace
{

using detail::YamlDocuments;
using detail::YamlNode;

// Walks both trees side by side; `seen` pairs each of our nodes with the yaml-cpp node it stood for,
// so that an alias must be the same node in both (and a cycle ends).
void expectSameTree(const YamlNode& ours, const YAML::Node& theirs, const std::string& at,
                    std::map<std::uint32_t, YAML::Node>& seen)
{
    SCOPED_TRACE(at);
    ASSERT_EQ(ours.isNull(), theirs.IsNull());
    ASSERT_EQ(ours.isScalar(), theirs.IsScalar());
    ASSERT_EQ(ours.isSequence(), theirs.IsSequence());
    ASSERT_EQ(ours.isMap(), theirs.IsMap());
    EXPECT_EQ(ours.mark().pos, theirs.Mark().pos);
    EXPECT_EQ(ours.mark().line, theirs.Mark().line);
    EXPECT_EQ(ours.mark().column, theirs.Mark().column);
    EXPECT_EQ(ours.tag(), theirs.Tag());
    if (const auto it = seen.find(ours.id()); it != seen.end())
    {
        EXPECT_TRUE(it->second.is(theirs)) << "an alias is one node in both trees";
        return;
    }
    seen.emplace(ours.id(), theirs);
    if (ours.isScalar())
    {
        EXPECT_EQ(ours.scalar(), theirs.Scalar());
    }
    if (ours.isSequence() || ours.isMap())
    {
        ASSERT_EQ(ours.size(), theirs.size());
        EXPECT_EQ(ours.style(), theirs.Style());
    }
    if (ours.isSequence())
    {
        for (std::size_t i = 0; i < ours.size(); ++i)
        {
            expectSameTree(ours[i], theirs[i], at + "[" + std::to_string(i) + "]", seen);
        }
    }
    if (ours.isMap())
    {
        std::size_t i = 0;
        for (auto it = theirs.begin(); it != theirs.end(); ++it, ++i)
        {
            expectSameTree(ours.key(i), it->first, at + ".key" + std::to_string(i), seen);
            expectSameTree(ours.value(i), it->second, at + ".value" + std::to_string(i), seen);
        }
    }
}

void expectSameAsYamlCpp(const std::string& text)
{
    SCOPED_TRACE(text.substr(0, 200));
    YamlDocuments ours;
    detail::parseYaml(text, "scene.yaml", ours);
    const std::vector<YAML::Node> theirs = YAML::LoadAll(text);
    ASSERT_EQ(static_cast<std::size_t>(ours.count), theirs.size());
    if (theirs.empty())
    {
        EXPECT_FALSE(ours.first.root().isDefined());
        return;
    }
    std::map<std::uint32_t, YAML::Node> seen;
    expectSameTree(ours.first.root(), theirs[0], "root", seen);
    if (theirs.size() > 1)
    {
        EXPECT_EQ(ours.second.pos, theirs[1].Mark().pos);
        EXPECT_EQ(ours.second.line, theirs[1].Mark().line);
        EXPECT_EQ(ours.second.column, theirs[1].Mark().column);
    }
}

TEST(YamlTree, BundledScenesAsYamlCppSeesThem)
{
    const std::filesystem::path dir = std::filesystem::path(FRONTIER_SOURCE_DIR) / "scenes";
    int files = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
    {
        if (entry.path().extension() == ".yaml")
        {
            expectSameAsYamlCpp(readTextOf(entry.path().string()));
            ++files;
        }
    }
    EXPECT_GT(files, 20);
}

TEST(YamlTree, EveryKindOfNodeAsYamlCppSeesIt)
{
    for (const char* text : {
             "",
             "# a comment only\n",
             "---\n...\n",
             "a: 1\nb: 'quoted'\nc: \"double\"\nd: ~\ne: null\nf:\ng: !!float 3\nh: !local 4\ni: !!str 5\n",
             "a: [1, 2, [3, {x: y}]]\nb:\n  - 1\n  -\n  - - 2\n    - 3\nc: {}\nd: []\n",
             "base: &b {type: box, size: [1, 2, 3]}\nuse: *b\nlist: [*b, *b]\nnum: &n 3\nagain: *n\n",
             "self: &s [1, *s]\n",
             "a: 1\na: 2\n? [complex, key]\n: value\n? plain\n",
             "a: |\n  block\n  text\nb: >\n  folded\n  text\n",
             "- 1\n- two\n- {three: 3}\n",
             "scalar at the root\n",
             "a: 1\n---\nb: 2\n---\n",
             "a: 1\n--- !tag\n[1]\n",
         })
    {
        expectSameAsYamlCpp(text);
    }
}

// Takes the items of `list:` one at a time and checks that the tree keeps none of them.
class CountingLists final : public detail::YamlListHandler
{
  public:
    void onRootValueBegin(const std::string& key) override { began.push_back(key); }
    bool takeItems(const std::string& key) override { return key == "list"; }
    void onItem(const std::string& key, std::size_t index, const YamlNode& item) override
    {
        EXPECT_EQ(key, "list");
        EXPECT_EQ(index, items);
        ++items;
        names.push_back(item.isMap() ? item.value(0).scalar() : item.scalar());
    }
    void onRootValueEnd(const std::string& key, const YamlNode& value) override
    {
        ended.push_back(key);
        if (key == "list")
        {
            EXPECT_TRUE(value.itemByItem());
            EXPECT_EQ(value.size(), items);
        }
    }
    std::vector<std::string> began, ended, names;
    std::size_t items = 0;
};

TEST(YamlTree, ItemsTakenOneAtATimeAreNotKept)
{
    std::string text = "name: many\nlist:\n";
    for (int i = 0; i < 1000; ++i)
    {
        text += "  - {name: item" + std::to_string(i) + ", size: [1, 2, 3], mass: 1}\n";
    }
    text += "after: [1, 2]\n";
    CountingLists lists;
    YamlDocuments documents;
    detail::parseYaml(text, "scene.yaml", documents, &lists);
    EXPECT_EQ(lists.items, 1000u);
    ASSERT_EQ(lists.names.size(), 1000u);
    EXPECT_EQ(lists.names[999], "item999");
    EXPECT_EQ(lists.began, (std::vector<std::string>{"name", "list", "after"}));
    EXPECT_EQ(lists.ended, lists.began);
    // The root map, its 3 keys, "many", the list (no items) and [1, 2]: 9 nodes of some 11 000.
    EXPECT_EQ(documents.first.nodeCount(), 9u);
    const YamlNode root = documents.first.root();
    ASSERT_EQ(root.size(), 3u);
    EXPECT_EQ(root.value(1).size(), 1000u);
    EXPECT_THROW(root.value(1)[0], std::logic_error); // its items are gone
    EXPECT_EQ(root.value(2)[1].scalar(), "2");
}

// An item that defines an anchor is kept: a later alias may name it.
TEST(YamlTree, AnItemWithAnAnchorIsKeptForItsAliases)
{
    CountingLists lists;
    YamlDocuments documents;
    detail::parseYaml("list:\n  - {name: a, shape: &s {r: 1}}\n  - {name: b}\nuse: *s\n", "scene.yaml",
                      documents, &lists);
    EXPECT_EQ(lists.names, (std::vector<std::string>{"a", "b"}));
    const YamlNode use = documents.first.root().value(1);
    ASSERT_TRUE(use.isMap());
    EXPECT_EQ(use.key(0).scalar(), "r");
    EXPECT_EQ(use.mark().line, 1);
    EXPECT_EQ(use.mark().column, 21); // at the anchor, as yaml-cpp marks it
}

// A ',' where a document should start: yaml-cpp 0.7 would return empty documents without end.
TEST(YamlTree, AStrayCommaStopsTheParse)
{
    YamlDocuments documents;
    const InputError e =
        captureInputError([&] { detail::parseYaml("a: 1\n---\n,\n", "plan.yaml", documents); });
    EXPECT_EQ(e.file(), "plan.yaml");
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.column(), 1);
    EXPECT_NE(e.message().find("unexpected ','"), std::string::npos) << e.message();
}

} // namespace
} // namespace frontier::io::test
