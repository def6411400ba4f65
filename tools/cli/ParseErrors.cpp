#include "ParseErrors.h"

#include <algorithm>
#include <cctype>
#include <vector>

namespace netsculpt::cli {

namespace {

/// Levenshtein distance between a and b (for "did you mean").
std::size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = above;
        }
    }
    return row[b.size()];
}

/// The long option of `command` nearest `given` ("--tolerence": "--tolerance"), "" when none is
/// near: within an edit per three letters of the option's name (at least one, at most three),
/// so that a short option is not offered for any word ("--bogus" is not "--out").
std::string nearestOption(const CLI::App& command, const std::string& given) {
    std::string best;
    std::size_t bestDistance = 4;
    for (const CLI::Option* option : command.get_options())
        for (const std::string& name : option->get_lnames()) {
            const std::size_t d = editDistance(given, "--" + name);
            const std::size_t near = std::clamp<std::size_t>((name.size() + 1) / 3, 1, 3);
            if (d <= near && d < bestDistance) {
                bestDistance = d;
                best = "--" + name;
            }
        }
    return best;
}

/// "unexpected arguments: ..." in the order given, with the option of `command` nearest a
/// misspelt one, or where a script's own options go.
std::string unexpectedArguments(const CLI::App& command, const std::vector<std::string>& extra) {
    std::string text = "unexpected arguments:";
    for (const std::string& argument : extra)
        text += " " + argument;
    for (const std::string& argument : extra)
        if (argument.starts_with("--"))
            if (const std::string near = nearestOption(command, argument); !near.empty())
                return text + " (" + argument + ": did you mean " + near + "?)";
    if (command.get_name() == "run" && extra.front().starts_with("-"))
        return text + " (a script's own arguments that start with - go after --: netsculpt run " +
               "SCRIPT -- " + extra.front() + ")";
    return text;
}

/// The commands of `app`, one a line with its description, and how to get a command's help.
std::string commandList(const CLI::App& app) {
    const auto commands = app.get_subcommands({});
    std::size_t width = 0;
    for (const CLI::App* command : commands)
        width = std::max(width, command->get_name().size());
    std::string text;
    for (const CLI::App* command : commands) {
        const std::string& name = command->get_name();
        text += "  " + name + std::string(width - name.size() + 2, ' ') +
                command->get_description() + "\n";
    }
    return text + "'netsculpt COMMAND --help' describes a command's arguments and options.";
}

/// A positional as the usage line writes it: DOC, FILE... (one or more), [ARGS...] (optional).
std::string positionalUsage(const CLI::Option& positional) {
    const std::string name =
        positional.get_name(true) + (positional.get_items_expected_max() > 1 ? "..." : "");
    return positional.get_required() ? name : "[" + name + "]";
}

/// "export needs FILE..., the files to write, by extension: ...; usage: netsculpt export DOC
/// FILE..." for the first required positional of `command` not given, "" when none is missing
/// (CLI11 says "files is required", naming neither the argument as the usage does nor what it is).
std::string missingArgument(const CLI::App& command) {
    const auto positionals =
        command.get_options([](const CLI::Option* option) { return option->get_positional(); });
    std::string usage = "netsculpt " + command.get_name();
    for (const CLI::Option* positional : positionals)
        usage += " " + positionalUsage(*positional);
    for (const CLI::Option* positional : positionals)
        if (positional->get_required() && positional->count() == 0) {
            std::string what = positional->get_description();
            if (!what.empty())
                what[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(what[0])));
            return command.get_name() + " needs " + positionalUsage(*positional) + ", " + what +
                   "; usage: " + usage;
        }
    return {};
}

} // namespace

std::string describeParseError(const CLI::App& app, const CLI::ParseError& e) {
    const auto commands = app.get_subcommands();
    std::vector<std::string> extra = app.remaining();
    if (extra.empty() && !commands.empty())
        extra = commands.front()->remaining();
    if (commands.empty() && !extra.empty() && !extra.front().starts_with("-")) {
        std::string names;
        for (const CLI::App* command : app.get_subcommands({}))
            names += (names.empty() ? "" : ", ") + command->get_name();
        return "unknown command '" + extra.front() + "'; the commands are " + names;
    }
    const CLI::App& command = commands.empty() ? app : *commands.front();
    if (dynamic_cast<const CLI::RequiredError*>(&e) != nullptr) {
        const std::string missing = commands.empty()
                                        ? "no command given; the commands are:\n" + commandList(app)
                                        : missingArgument(command);
        if (!missing.empty())
            return (extra.empty() ? "" : unexpectedArguments(command, extra) + ", and ") + missing;
    }
    if (dynamic_cast<const CLI::ExtrasError*>(&e) == nullptr || extra.empty())
        return e.what();
    return unexpectedArguments(command, extra);
}

} // namespace netsculpt::cli
