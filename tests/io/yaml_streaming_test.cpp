// tests/io/yaml_streaming_test.cpp: the scene reader takes `bodies:` and `joints:` item by item
// while it parses (io/yaml_scene.cpp, SceneLists), yet a scene means the same whatever the order
// of its top-level keys and however its YAML is written, and the error it reports is the one the
// scene's rules meet first (simulation, contact and camera before the bodies, then the models, then
// the joints), wherever the two errors sit in the file.
#include "io/scene.h"
#include "io_test_util.h"
#include "model_text.h"

#include <filesystem>
#include <functional>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

namespace frontier::io::test
{
namespace
{

std::string loadedText(const std::function<core::Model(LoadReport*)>& load)
{
    LoadReport report;
    const core::Model model = load(&report);
    return modelText(model, &report);
}

// The scene's top-level keys in the order `keys` gives (the others after them, in theirs), every
// collection in `style`.
std::string rewritten(const YAML::Node& scene, const std::vector<std::string>& keys,
                      YAML::EmitterStyle::value style)
{
    YAML::Node out(YAML::NodeType::Map);
    for (const std::string& key : keys)
    {
        if (scene[key])
        {
            out[key] = YAML::Clone(scene[key]);
        }
    }
    for (auto it = scene.begin(); it != scene.end(); ++it)
    {
        if (!out[it->first.Scalar()])
        {
            out[it->first.Scalar()] = YAML::Clone(it->second);
        }
    }
    std::function<void(YAML::Node)> setStyle = [&](YAML::Node node)
    {
        if (node.IsMap() || node.IsSequence())
        {
            node.SetStyle(style);
            for (auto it = node.begin(); it != node.end(); ++it)
            {
                setStyle(node.IsMap() ? it->second : *it);
            }
        }
    };
    if (style != YAML::EmitterStyle::Default)
    {
        for (auto it = out.begin(); it != out.end(); ++it)
        {
            setStyle(it->second);
        }
    }
    YAML::Emitter emitter;
    emitter << out;
    return emitter.c_str();
}

// Every bundled scene loads to the same model, field by field: from its file, from its text (the
// batch path), and rewritten with its keys in other orders (joints first, models last, reversed) and
// in flow or block style.
TEST(YamlStreaming, BundledScenesMeanTheSameInAnyOrderAndStyle)
{
    const std::filesystem::path dir = std::filesystem::path(FRONTIER_SOURCE_DIR) / "scenes";
    int scenes = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
    {
        if (entry.path().extension() != ".yaml")
        {
            continue;
        }
        const std::string path = entry.path().string();
        SCOPED_TRACE(path);
        const std::string text = readTextOf(path);
        const std::string expected = loadedText([&](LoadReport* r) { return loadScene(path, {}, r); });
        EXPECT_EQ(loadedText([&](LoadReport* r) { return loadSceneFromString(text, path, {}, r); }),
                  expected);
        const YAML::Node scene = YAML::Load(text);
        std::vector<std::string> reversed;
        for (auto it = scene.begin(); it != scene.end(); ++it)
        {
            reversed.insert(reversed.begin(), it->first.Scalar());
        }
        std::vector<std::string> modelsLast;
        for (const std::string& key : reversed)
        {
            if (key != "models")
            {
                modelsLast.insert(modelsLast.begin(), key);
            }
        }
        modelsLast.emplace_back("models");
        const std::vector<std::pair<std::vector<std::string>, YAML::EmitterStyle::value>> variants = {
            {{"joints", "models"}, YAML::EmitterStyle::Default},
            {modelsLast, YAML::EmitterStyle::Flow},
            {reversed, YAML::EmitterStyle::Block},
            {{"models", "joints", "bodies"}, YAML::EmitterStyle::Block},
        };
        for (const auto& [keys, style] : variants)
        {
            const std::string variant = rewritten(scene, keys, style);
            SCOPED_TRACE(variant.substr(0, 300));
            EXPECT_EQ(loadedText([&](LoadReport* r) { return loadSceneFromString(variant, path, {}, r); }),
                      expected);
        }
        ++scenes;
    }
    EXPECT_GT(scenes, 20);
}

// A URDF model's joints come before the scene's own joints (and its bodies after the scene's),
// wherever `models:` stands: the joints read before a later `models:` are read again after it.
TEST(YamlStreaming, ModelsAfterTheJointsStillComeFirstAmongTheJoints)
{
    TempDir dir;
    std::filesystem::copy_file(std::filesystem::path(FRONTIER_SOURCE_DIR) / "scenes/doll.urdf",
                               dir.file("doll.urdf"));
    const std::string bodies = "bodies:\n"
                               "  - {name: box, mass: 1, shape: &s {type: box, size: [0.1, 0.1, 0.1]}, "
                               "position: [0, 0, 3]}\n"
                               "  - {name: box2, mass: 1, shape: *s, position: [0, 0, 4]}\n";
    const std::string joints =
        "joints:\n"
        "  - {name: hang, type: ball, parent: a_pelvis, child: box, anchor: [0, 0, 2.5]}\n"
        "  - {name: link, type: ball, parent: box, child: box2, anchor: [0, 0, 3.5]}\n";
    const std::string models = "models:\n  - {urdf: doll.urdf, prefix: a_, position: [0, 0, 1]}\n";
    const std::string expected = loadedText(
        [&](LoadReport* r) { return loadScene(dir.write("a.yaml", bodies + models + joints), {}, r); });
    for (const std::string& text : {bodies + joints + models, joints + bodies + models,
                                    models + joints + bodies, joints + models + bodies})
    {
        SCOPED_TRACE(text);
        std::string got =
            loadedText([&](LoadReport* r) { return loadScene(dir.write("a.yaml", text), {}, r); });
        EXPECT_EQ(got, expected);
    }
    const core::Model model = loadScene(dir.write("a.yaml", bodies + joints + models));
    ASSERT_GE(model.joints.size(), 3u);
    EXPECT_EQ(model.joints[model.joints.size() - 2].name, "hang");
    EXPECT_EQ(model.joints.back().name, "link");
    EXPECT_EQ(model.bodies[0].name, "box");
    EXPECT_EQ(model.bodies[2].name.substr(0, 2), "a_");
}

// Two errors: the one of the part the scene's rules read first is reported, not the one first in
// the file.
TEST(YamlStreaming, TheErrorReportedIsTheFirstByTheScenesRules)
{
    const std::string badBody = "bodies:\n  - {name: a, mass: heavy, shape: {type: sphere, radius: 0.1}}\n";
    const std::string goodBody = "bodies:\n  - {name: a, mass: 1, shape: {type: sphere, radius: 0.1}}\n";
    const std::string badJoint =
        "joints:\n  - {name: j, type: ball, parent: world, child: b, anchor: [0, 0, 0]}\n";
    const std::string badSimulation = "simulation: {dt: fast}\n";
    const std::string badKey = "colour: red\n";
    // The simulation before the bodies.
    EXPECT_NE(yamlError(badBody + badSimulation).message().find("'dt' in 'simulation'"), std::string::npos);
    // A key the scene does not know before anything else.
    EXPECT_NE(yamlError(badBody + badJoint + badKey).message().find("unknown key 'colour'"),
              std::string::npos);
    // The bodies before the joints, wherever they are.
    EXPECT_NE(yamlError(badJoint + badBody).message().find("'mass' in body 'a'"), std::string::npos);
    EXPECT_NE(yamlError(badBody + badJoint).message().find("'mass' in body 'a'"), std::string::npos);
    // The joints' error once the bodies are fine, at its line.
    const InputError e = yamlError(goodBody + badJoint + badSimulation.substr(0, 0));
    EXPECT_EQ(e.line(), 4);
    EXPECT_NE(e.message().find("unknown body 'b'"), std::string::npos);
    // A YAML syntax error anywhere before any error of the scene's content.
    EXPECT_NE(yamlError(badBody + "simulation: {dt: [}\n").message().find("invalid YAML"), std::string::npos);
    // Several documents before the bodies of the first.
    EXPECT_NE(yamlError(badBody + "---\nbodies: []\n").message().find("2 YAML documents"), std::string::npos);
}

// The bodies and joints of a long chain, read item by item, are the chain (names, order, links).
TEST(YamlStreaming, ALongChainKeepsItsOrder)
{
    std::string text = "bodies:\n";
    constexpr int cLinks = 3000;
    for (int i = 0; i < cLinks; ++i)
    {
        text += "  - {name: link" + std::to_string(i) +
                ", shape: {type: box, size: [0.08, 0.02, 0.02]}, mass: 0.1, "
                "position: [" +
                std::to_string(0.1 * i) + ", 0, 2]}\n";
    }
    text += "joints:\n";
    for (int i = 0; i < cLinks; ++i)
    {
        text += "  - {name: j" + std::to_string(i) +
                ", type: ball, parent: " + (i == 0 ? std::string("world") : "link" + std::to_string(i - 1)) +
                ", child: link" + std::to_string(i) + ", anchor: [" + std::to_string(0.1 * i - 0.05) +
                ", 0, 2]}\n";
    }
    const core::Model model = loadSceneFromString(text, "chain.yaml");
    ASSERT_EQ(model.bodies.size(), static_cast<std::size_t>(cLinks));
    ASSERT_EQ(model.joints.size(), static_cast<std::size_t>(cLinks));
    for (int i = 0; i < cLinks; ++i)
    {
        const auto k = static_cast<std::size_t>(i);
        EXPECT_EQ(model.bodies[k].name, "link" + std::to_string(i));
        EXPECT_EQ(model.joints[k].child, i);
        EXPECT_EQ(model.joints[k].parent, i - 1);
    }
    const InputError e =
        yamlError(text + "  - {name: j0, type: ball, parent: world, child: link1, anchor: [0, 0, 2]}\n");
    EXPECT_EQ(e.line(), 2 * cLinks + 3);
    EXPECT_NE(e.message().find("duplicate joint name 'j0' (first defined at line " +
                               std::to_string(cLinks + 3) + ")"),
              std::string::npos)
        << e.message();
}

} // namespace
} // namespace frontier::io::test
