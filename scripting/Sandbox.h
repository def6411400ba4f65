#pragma once
// The sandbox a script runs in by default (scripts are shared between studios). With it:
// - absent-by-refusal (calling them raises "<name>: not allowed in a script ..."): os.execute,
//   os.exit, os.remove, os.rename, os.tmpname, os.setlocale, io.popen, io.tmpfile,
//   package.loadlib, package.searchpath and every debug function but traceback and getinfo;
// - reading (io.open with mode "r"/"rb", io.lines, io.input, dofile, loadfile, require of .lua
//   modules, doc:import_rails, ns.open) is limited to the script's folder and the output folder;
//   relative paths resolve against the script's folder;
// - io.open for writing, io.output(file name) are refused: a script writes only through
//   doc:save / doc:export / doc:write_report, into the output folder. Relative paths resolve
//   inside the output folder; absolute paths, and `..` or links that lead out of it, are refused;
// - require finds Lua modules in the script's folder and the output folder only (package.path
//   and package.cpath are ignored); C modules other than netsculpt cannot be loaded;
// - load and loadfile accept text chunks only (binary chunks can crash the VM).
// The host's --unsafe lifts all of this (netsculpt's own writes still resolve relative paths
// inside the output folder, and may then also be absolute).

#include "scripting/Context.h"
#include "scripting/LuaSupport.h"

#include <filesystem>
#include <string>
#include <vector>

namespace netsculpt::lua {

/// Where a sandboxed script may read and find modules: its own folder, the output folder and the
/// library folders (--lib), in that order.
std::vector<std::filesystem::path> readableFolders(const ScriptContext& context);
/// The file a script may read at `path` (as given by the script), for the call `call`.
/// Throws UserError saying which folders are allowed when the sandbox refuses it.
std::filesystem::path resolveReadPath(const ScriptContext& context, const std::string& path,
                                      const char* call);
/// Throws UserError naming `call` when `text` is no file name: empty, or holding a NUL character.
void checkFileName(const std::string& text, const char* call);
/// The file name a writing call (doc:save, doc:export, ...) takes as its argument `index`.
struct FileArgument {
    std::string given;     ///< as the script gave it
    std::string extension; ///< its ending in lower case, without the dot ("" for none)
};
/// A string argument checked as a file name (checkFileName), with its ending.
FileArgument checkFileArgument(const Call& call, int index);
/// The file a script may write at `path`; creates its parent folders inside the output folder.
/// Throws UserError when the sandbox refuses it (nothing is created then).
std::filesystem::path resolveWritePath(const ScriptContext& context, const std::string& path,
                                       const char* call);

/// Installs the sandbox into a state whose standard libraries are open (context(L).sandboxed).
void installSandbox(lua_State* L);

} // namespace netsculpt::lua
