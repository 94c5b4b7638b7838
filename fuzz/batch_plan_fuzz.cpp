// fuzz/batch_plan_fuzz.cpp: libFuzzer target for `frontier batch` plans: app::readBatchPlan (the
// plan's checks, the expansion of scenes and `vary:` into jobs), then the first jobs' scenes as the
// batch runs them (app::loadBatchScene: the scene paths set in the scene's text, which is loaded
// again, the seed's perturbation) and a few steps of each. The plan sits in a folder holding copies
// of three bundled scenes (ball.yaml, pendulum.yaml, stack.yaml) for its `scenes:` to name or glob.
#include "app/batch/plan.h"
#include "app/batch/scene.h"
#include "fuzz/fuzz_input.h"
#include "fuzz/fuzz_steps.h"

#include <algorithm>

namespace
{

void copyBundledScenes()
{
    namespace fs = std::filesystem;
    const fs::path scenes = fs::path(FRONTIER_SOURCE_DIR) / "scenes";
    const std::pair<const char*, const char*> copies[] = {{"bouncing_ball.yaml", "ball.yaml"},
                                                          {"pendulum.yaml", "pendulum.yaml"},
                                                          {"box_stack.yaml", "stack.yaml"}};
    for (const auto& [from, to] : copies)
    {
        fs::copy_file(scenes / from, frontier::fuzz::scratchDir() / to, fs::copy_options::overwrite_existing);
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    using namespace frontier;
    static const bool copied = (copyBundledScenes(), true);
    (void)copied;
    constexpr std::size_t cJobs = 2;
    constexpr long cSteps = 5;
    const std::string path = fuzz::writeInput(data, size, "plan.yaml");
    return fuzz::expectInputErrorOnly(
        [&]
        {
            const app::BatchPlan plan = app::readBatchPlan(path);
            for (std::size_t i = 0; i < std::min(cJobs, plan.jobs.size()); ++i)
            {
                fuzz::stepModel(app::loadBatchScene(plan, plan.jobs[i], io::UrdfOptions{}).loaded.model,
                                cSteps);
            }
        });
}
