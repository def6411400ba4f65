#pragma once
// The CLI's usage errors in the user's terms (CLI11's own call an unknown command or none "A
// subcommand is required", say "files is required" of a missing argument without saying what it
// is, list unexpected arguments backwards, and read the value after a misspelt option as the
// next positional, listing the one the user meant as unexpected).

#include <CLI/CLI.hpp>

#include <string>

namespace netsculpt::cli {

/// The message for a parse error of `app`: an unknown command named, with the commands there are;
/// no command given, with the commands one a line and how to get their help;
/// a command's argument missing, named as its usage line names it, with what it is;
/// an option it does not have named, without the arguments CLI11 then misread (the value after it
/// taken for a positional), with the option nearest a misspelt one ("unknown option --tolerence
/// (did you mean --tolerance?)"); else unexpected arguments in the order given; else CLI11's
/// message.
std::string describeParseError(const CLI::App& app, const CLI::ParseError& e);

} // namespace netsculpt::cli
