#include "ParseErrors.h"

#include <algorithm>
#include <cctype>
#include <utility>
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

/// The option an argument names ("--tolerence" of "--tolerence=1", "-x"), "" when it is a value
/// ("out/x.netj", "-3", "-") or an option `command` or the program has (given after "--").
std::string unknownOption(const CLI::App& command, const std::string& argument) {
    if (argument.size() < 2 || argument[0] != '-' ||
        std::isdigit(static_cast<unsigned char>(argument[1])) != 0 || argument[1] == '.')
        return {};
    const std::string name = argument.substr(0, argument.find('='));
    for (const CLI::App* app = &command; app != nullptr; app = app->get_parent())
        if (app->get_option_no_throw(name) != nullptr)
            return {};
    return name;
}

/// "unknown option --tolerence (did you mean --tolerance?)" when arguments left over name options
/// `command` does not have, with the nearest option of each misspelt one, or where a script's own
/// options go. Only the options are named: CLI11 took the value given after one for the next
/// positional (`relax --tolerence 1 x.netj` read 1 as the document), so the arguments left over
/// beside them are not the ones the user gave too many. Else "unexpected arguments: ..." in the
/// order given.
std::string unexpectedArguments(const CLI::App& command, const std::vector<std::string>& extra) {
    std::vector<std::pair<std::string, std::string>> unknown; // the option, the argument
    for (const std::string& argument : extra)
        if (std::string name = unknownOption(command, argument); !name.empty())
            unknown.emplace_back(std::move(name), argument);
    if (unknown.empty()) {
        std::string text = "unexpected arguments:";
        for (const std::string& argument : extra)
            text += " " + argument;
        return text;
    }
    std::string text = unknown.size() == 1 ? "unknown option" : "unknown options";
    for (std::size_t i = 0; i < unknown.size(); ++i) {
        const auto& [name, argument] = unknown[i];
        text += (i == 0 ? " " : ", ") + name;
        if (const std::string near = nearestOption(command, name); !near.empty())
            text += " (did you mean " + near + "?)";
        else if (command.get_name() == "run" && i == 0)
            text += " (a script's own arguments that start with - go after --: netsculpt run "
                    "SCRIPT -- " +
                    argument + ")";
    }
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
