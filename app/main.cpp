// app/main.cpp: the `frontier` executable: registers the commands (each in its app/NAME_command.cpp),
// parses the command line (CLI11), runs the command given, and turns a signal into its exit code.
#include "app/commands.h"
#include "core/interrupt.h"
#include "io/input_digest.h"
#include "io/suggest.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>
#include <optional>

namespace
{
using namespace frontier::app;

// A first word that names no command: say so, instead of CLI11's "A subcommand is required".
std::optional<int> refuseUnknownCommand(const std::vector<Command>& commands, int argc, char** argv)
{
    if (argc <= 1 || argv[1][0] == '-')
    {
        return std::nullopt;
    }
    std::vector<std::string> names;
    for (const Command& command : commands)
    {
        names.push_back(command.parser->get_name());
    }
    if (std::find(names.begin(), names.end(), argv[1]) != names.end())
    {
        return std::nullopt;
    }
    std::cerr << "frontier: unknown command '" << argv[1] << "'"
              << frontier::io::detail::suggestionSuffix(argv[1], names, true)
              << "\nRun with --help for more information.\n";
    return cExitBadInput;
}

// CLI11's parse; an exit code when the command line asks for help or the version, or is wrong.
std::optional<int> parse(CLI::App& app, int argc, char** argv)
{
    try
    {
        app.parse(argc, argv);
        return std::nullopt;
    }
    catch (const CLI::CallForHelp& e)
    {
        return app.exit(e);
    }
    catch (const CLI::CallForVersion& e)
    {
        return app.exit(e);
    }
    catch (const CLI::ParseError& e)
    {
        app.exit(e);
        return cExitBadInput;
    }
}

// Runs the one command parsed. A signal at a checkpoint outside the step loop (while loading,
// core/interrupt.h), where the command has nothing to clean up, exits with the signal's code.
int runParsed(const std::vector<Command>& commands)
{
    try
    {
        for (const Command& command : commands)
        {
            if (command.parser->parsed())
            {
                return command.run();
            }
        }
        return cExitBadInput; // not reached: the parser requires one command
    }
    catch (const frontier::core::Interrupted& e)
    {
        std::cerr << "frontier: " << e.what() << "\n";
        return frontier::core::interruptedExitCode(e.signal());
    }
}
} // namespace

int main(int argc, char** argv)
{
    CLI::App app{"Frontier: articulated rigid bodies, joint and contact impulses solved exactly in O(n)"};
    app.require_subcommand(1);
    app.option_defaults()->always_capture_default(); // --help shows each option's default
    app.set_version_flag("--version", frontier::io::frontierVersion());

    // In the order --help lists them.
    const std::vector<Command> commands = {
        addRunCommand(app),       addInfoCommand(app),  addRenderCommand(app), addCheckCommand(app),
        addStabilityCommand(app), addSweepCommand(app), addBatchCommand(app)};
    if (const std::optional<int> code = refuseUnknownCommand(commands, argc, argv))
    {
        return *code;
    }
    if (const std::optional<int> code = parse(app, argc, argv))
    {
        return *code;
    }
    return runParsed(commands);
}
