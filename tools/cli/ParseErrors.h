#pragma once
// The CLI's usage errors in the user's terms (CLI11's own call an unknown command or none "A
// subcommand is required", say "files is required" of a missing argument without saying what it
// is, and list unexpected arguments backwards).

#include <CLI/CLI.hpp>

#include <string>

namespace netsculpt::cli {

/// The message for a parse error of `app`: an unknown command named, with the commands there are;
/// no command given, with the commands one a line and how to get their help;
/// a command's argument missing, named as its usage line names it, with what it is;
/// unexpected arguments in the order given, with the option nearest a misspelt one ("--tolerence:
/// did you mean --tolerance?"); else CLI11's message.
std::string describeParseError(const CLI::App& app, const CLI::ParseError& e);

} // namespace netsculpt::cli
