// Relaxation: doc:relax{...}, doc:last_relax(); ns.backends().

#include "io/Report.h"
#include "model/Error.h"
#include "physics/Backends.h"
#include "scripting/Context.h"
#include "scripting/Handles.h"
#include "scripting/Limits.h"
#include "scripting/Wrap.h"

namespace netsculpt::lua {

namespace {

Wind windArg(const TableArgs& args) {
    const Call& call = args.call();
    const int at = args.push("wind");
    if (lua_type(call.L, at) != LUA_TTABLE)
        call.bad("wind", at, "a table {direction = {x, y, z}, pressure = N per metre of rope}");
    const TableArgs wind(call, at, {"direction", "pressure"});
    Wind w;
    w.direction = wind.vec3("direction");
    w.pressure = wind.finite("pressure", std::nullopt);
    if (w.pressure < 0)
        call.fail("argument 'wind.pressure' must be a number of N/m >= 0, got " +
                  formatNumber(w.pressure));
    (void)validatedWindDirection(w);
    args.pop();
    return w;
}

DocumentRelaxOptions relaxArgs(const Call& call) {
    DocumentRelaxOptions options;
    RelaxOptions& o = options.solver;
    if (!lua_isnoneornil(call.L, 2)) {
        const TableArgs args(call, 2,
                             {"tolerance", "max_seconds", "max_steps", "backend", "wind",
                              "continuation", "threads"});
        o.tolerance = args.positive("tolerance", o.tolerance);
        if (o.tolerance > kMaxTolerance)
            call.bad("tolerance", args.push("tolerance"),
                     "a number > 0 and at most " + formatNumber(kMaxTolerance));
        o.maxSeconds = args.positive("max_seconds", o.maxSeconds);
        o.maxSteps = args.whole("max_steps", o.maxSteps, -1, INT64_MAX);
        options.backend = args.choice("backend", relaxerNames(), options.backend);
        if (args.has("wind"))
            o.wind = windArg(args);
        o.continuation = args.boolean("continuation", o.continuation);
        o.threads = int(args.whole("threads", 0, 0, 1024));
    }
    const ScriptContext& ctx = context(call.L);
    if (!ctx.backendOverride.empty())
        options.backend = ctx.backendOverride;
    o.progress = ctx.relaxProgress;
    o.cancel = ctx.interrupt;
    return options;
}

/// The result table of `doc` (at stack index docIndex: unsettled_at.piece is its handle), with
/// the bars its shape stretches beyond what rope can (overstretched_bars).
void pushRelaxResult(lua_State* L, const Document& doc, const RelaxResult& r, int docIndex) {
    lua_createtable(L, 0, 8);
    setBoolean(L, "converged", r.converged);
    setNumber(L, "residual", r.residual);
    setInteger(L, "steps", r.steps);
    setInteger(L, "evaluations", r.forceEvaluations);
    setNumber(L, "seconds", r.seconds);
    setString(L, "backend", r.backend);
    setString(L, "stop_reason", r.stopReason);
    if (r.unsettledAt) {
        lua_createtable(L, 0, 3);
        pushPiece(L, docIndex, r.unsettledAt->piece);
        lua_setfield(L, -2, "piece");
        setInteger(L, "row", r.unsettledAt->row);
        setInteger(L, "column", r.unsettledAt->column);
        lua_setfield(L, -2, "unsettled_at");
    }
    setInteger(L, "overstretched_bars",
               std::int64_t(countOverstretchedBars(doc.compiled().system)));
}

/// doc:relax{tolerance, max_seconds, max_steps, backend, wind = {direction, pressure},
/// continuation, threads} -> {converged, residual, steps, evaluations, seconds, backend,
/// stop_reason, unsettled_at = {piece, row, column} when not converged, overstretched_bars: the
/// bars stretched beyond what rope can (Report.h)}.
int w_relax(Call& call) {
    Document& doc = checkDocument(call);
    const DocumentRelaxOptions options = relaxArgs(call);
    const RelaxResult result = doc.relax(options);
    ScriptContext& ctx = context(call.L);
    if (ctx.relaxFinished)
        ctx.relaxFinished(doc, result);
    if (interruptRequested(ctx)) { // the script goes no further; the shape reached is kept
        ctx.stop = Stop::Interrupted;
        throw UserError(interruptedMessage());
    }
    pushRelaxResult(call.L, doc, result, 1);
    return 1;
}

/// doc:last_relax() -> the last relax result (as relax{} returns it, with the shape's
/// overstretched_bars now), or nil before any.
int w_last_relax(Call& call) {
    const Document& doc = checkDocument(call);
    const RelaxResult& r = doc.lastRelax();
    if (r.stopReason.empty() && r.steps == 0 && !r.converged) {
        lua_pushnil(call.L);
        return 1;
    }
    pushRelaxResult(call.L, doc, r, 1);
    return 1;
}

/// ns.backends() -> {"auto", "rk4", ...}: the relaxation backends of this build.
int w_backends(Call& call) {
    const std::vector<std::string> names = relaxerNames();
    lua_createtable(call.L, int(names.size()), 0);
    for (std::size_t i = 0; i < names.size(); ++i) {
        lua_pushstring(call.L, names[i].c_str());
        lua_rawseti(call.L, -2, lua_Integer(i + 1));
    }
    return 1;
}

} // namespace

void addRelaxMethods(lua_State* L) {
    setMethods(L, {{"relax", entry<w_relax>, kKeywordTable},
                   {"last_relax", entry<w_last_relax>, 0}});
}

void addModuleRelaxFunctions(lua_State* L) {
    setFunctions(L, {{"backends", entry<w_backends>, 0}});
}

} // namespace netsculpt::lua
