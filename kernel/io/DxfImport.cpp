// DXF rails (Import.h): the text decoded (DxfText), its syntax checked (DxfScan), read by dxflib
// (DxfCollector), block references placed (DxfBlocks); here the units, the layers that are read,
// LINE/ARC chains, and the messages for a drawing without rails.

#include "geometry/Curve.h"
#include "io/Chains.h"
#include "io/DxfBlocks.h"
#include "io/DxfCollector.h"
#include "io/DxfText.h"
#include "io/ImportDetail.h"
#include "io/IoText.h"
#include "model/Error.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <map>
#include <optional>
#include <set>

namespace netsculpt::io {

namespace {

/// $INSUNITS codes of the DXF reference, in metres (0 = unitless is not here).
struct DxfUnit {
    int code;
    const char* name;
    double metres;
};
constexpr std::array<DxfUnit, 24> kDxfUnits{{
    {1, "inches", 0.0254},
    {2, "feet", 0.3048},
    {3, "miles", 1609.344},
    {4, "millimetres", 1e-3},
    {5, "centimetres", 1e-2},
    {6, "metres", 1.0},
    {7, "kilometres", 1e3},
    {8, "microinches", 2.54e-8},
    {9, "mils", 2.54e-5},
    {10, "yards", 0.9144},
    {11, "angstroms", 1e-10},
    {12, "nanometres", 1e-9},
    {13, "microns", 1e-6},
    {14, "decimetres", 0.1},
    {15, "decametres", 10.0},
    {16, "hectometres", 100.0},
    {17, "gigametres", 1e9},
    {18, "astronomical units", 1.495978707e11},
    {19, "light years", 9.4607304725808e15},
    {20, "parsecs", 3.0856775814913673e16},
    {21, "US survey feet", 1200.0 / 3937.0},
    {22, "US survey inches", 100.0 / 3937.0},
    {23, "US survey yards", 3600.0 / 3937.0},
    {24, "US survey miles", 6336000.0 / 3937.0},
}};

double fileUnits(const std::string& file, const std::optional<int>& insunits,
                 const ImportOptions& options) {
    const int code = insunits.value_or(0);
    std::string names;
    for (const auto& u : unitNames())
        names += (names.empty() ? "" : ", ") + u;
    if (code == 0) {
        if (!options.units.empty())
            return metresPerUnit(options.units);
        throw UserError(
            file + ": the drawing has no units ($INSUNITS is " +
            (insunits ? std::string("0, unitless") : std::string("not set")) +
            "); set the drawing units in the CAD program, or say which unit its numbers are "
            "in when importing (units = one of " +
            names + ")");
    }
    const auto it = std::find_if(kDxfUnits.begin(), kDxfUnits.end(),
                                 [&](const DxfUnit& u) { return u.code == code; });
    if (it == kDxfUnits.end())
        throw UserError(
            file + ": $INSUNITS is " + std::to_string(code) +
            ", which is not a DXF unit code (1 to 24, or 0 for unitless); fix the drawing's units "
            "in the CAD program");
    if (!options.units.empty()) {
        const double asked = metresPerUnit(options.units);
        if (std::abs(asked - it->metres) > 1e-12 * it->metres)
            throw UserError(file + ": the drawing is in " + it->name + " ($INSUNITS " +
                            std::to_string(code) + ") but units = \"" + options.units +
                            "\" was given; leave units out or fix the drawing");
    }
    return it->metres;
}

/// ASCII lower case: DXF layer names are compared without case, as CAD programs do.
std::string folded(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return text;
}

/// Which layers are read: those of ImportOptions::layers when given (checked against the
/// drawing's), else every layer that is drawn: not frozen, not off, not Defpoints.
class LayerChoice {
  public:
    LayerChoice(const std::string& file, const DxfScan& scan,
                const std::vector<std::string>& askedNames) {
        std::set<std::string> names; // the LAYER table's and those entities name
        for (const DxfLayer& layer : scan.layers) {
            names.insert(layer.name);
            if (layer.frozen())
                frozen_.insert(folded(layer.name));
            if (layer.off())
                off_.insert(folded(layer.name));
        }
        for (const DxfEntity& e : scan.entities)
            names.insert(e.layer);
        std::set<std::string> known;
        for (const auto& name : names)
            known.insert(folded(name));
        for (const auto& name : askedNames) {
            if (!known.count(folded(name)))
                throw UserError(file + ": layers names the layer " + quoted(name, 80) +
                                ", which the drawing does not have; its layers are " +
                                listed({names.begin(), names.end()}));
            asked_.insert(folded(name));
        }
        asked = askedNames;
    }

    /// The layers ImportOptions::layers named, as given; empty when every drawn layer is read.
    std::vector<std::string> asked;

    /// Whether `p` is read; `noteSkipped` records a layer left out because it is not drawn.
    bool reads(const Placed& p, bool noteSkipped = true) {
        if (p.entity->netsculptBar())
            return false; // a bar of a net netsculpt wrote (DxfExport.h), on any layer
        if (!asked_.empty()) {
            bool listed = asked_.count(folded(p.layer)) > 0;
            for (const auto& layer : p.insertLayers)
                listed = listed || asked_.count(folded(layer)) > 0;
            if (!listed && noteSkipped)
                unchosen_.insert(p.layer);
            return listed;
        }
        const std::string layer = folded(p.layer);
        bool hidden = frozen_.count(layer) || off_.count(layer) || layer == "defpoints";
        for (const auto& outer : p.insertLayers)
            hidden = hidden || frozen_.count(folded(outer));
        if (hidden && noteSkipped)
            skipped_.insert(p.layer);
        return !hidden;
    }
    /// The layers of entities reads() left out because they are not drawn.
    const std::set<std::string>& skipped() const { return skipped_; }
    /// The layers of entities reads() left out because `asked` does not name them.
    const std::set<std::string>& unchosen() const { return unchosen_; }

  private:
    std::set<std::string> frozen_, off_, asked_, skipped_, unchosen_;
};

/// Why a drawing gave no rails: what it holds instead.
[[noreturn]] void refuseEmpty(const std::string& file, const DxfScan& scan,
                              const LayerChoice& layers) {
    std::map<std::string, int> model, paper;
    for (const auto& e : scan.entities)
        if (e.block.empty())
            ++(e.paperSpace ? paper : model)[e.type];
    const auto counts = [](const std::map<std::string, int>& types) {
        std::string seen;
        for (const auto& [type, count] : types)
            seen += (seen.empty() ? "" : ", ") + std::to_string(count) + " " + type;
        return seen;
    };
    std::string what = file + ": holds no rails (SPLINE, LWPOLYLINE, POLYLINE, LINE, ARC, CIRCLE "
                              "or a block reference of them in model space)";
    if (!layers.asked.empty()) {
        std::string held;
        for (const auto& name : layers.asked) {
            std::map<std::string, int> on;
            for (const auto& e : scan.entities)
                if (e.block.empty() && !e.paperSpace && folded(e.layer) == folded(name))
                    ++on[e.type];
            held += (held.empty() ? "" : "; ") + name + ": " +
                    (on.empty() ? std::string("nothing") : counts(on));
        }
        what += " on the layers chosen by layers = {...} (" + held + ")";
        if (!layers.unchosen().empty())
            throw UserError(what + "; its rails are on " +
                            listed({layers.unchosen().begin(), layers.unchosen().end()}) +
                            "; name those layers in layers = {...} to read them");
        throw UserError(what + (model.empty() ? std::string("; the drawing has no entities")
                                              : "; the drawing has " + counts(model)));
    }
    if (!layers.skipped().empty())
        throw UserError(what +
                        "; its rails are on layers that are not drawn (frozen, off or "
                        "Defpoints): " +
                        listed({layers.skipped().begin(), layers.skipped().end()}) +
                        "; name them in layers = {...} to read them");
    if (model.empty() && !paper.empty())
        throw UserError(what + "; its only entities (" + counts(paper) +
                        ") are in paper space (a layout); move them to model space in the CAD "
                        "program");
    throw UserError(
        what + (model.empty() ? std::string("; it has no entities") : "; it has " + counts(model)));
}

} // namespace

std::vector<NamedCurve> importDxf(const std::filesystem::path& path, const ImportOptions& options) {
    const std::string file = displayName(path);
    const std::string text = decodeDxfText(file, readWholeFile(path));
    const DxfScan scan = scanDxf(file, text);
    const DxfDrawing drawing = collectDxf(file, scan, text);
    const double metres = fileUnits(file, drawing.insunits, options);
    LayerChoice layers(file, scan, options.layers);
    const PlacedDrawing placed = placeDrawing(file, drawing);
    // An entity that cannot be a rail is refused only when it would be read: the first in file
    // order (of its model-space entity or outermost INSERT).
    const std::pair<Placed, std::string>* refused = nullptr;
    for (const auto& refusal : placed.refusals)
        if (layers.reads(refusal.first, false) &&
            (!refused || refusal.first.order < refused->first.order))
            refused = &refusal;
    if (refused)
        throw UserError(file + ": " + refused->first.where + ": " + refused->second);

    std::vector<SourcedCurve> all;
    for (const auto& [p, spec] : placed.curves)
        if (layers.reads(p))
            all.push_back({{p.name, spec}, p.where, p.order});
    for (const auto& [p, spline] : placed.splines)
        if (layers.reads(p)) {
            checkCoordinates(file, p.where, spline.control, metres);
            SourcedCurve curve = splineCurve(file, spline, p.name, p.where);
            curve.order = p.order;
            all.push_back(std::move(curve));
        }
    std::map<std::pair<std::string, std::string>, std::vector<ChainPart>> chains;
    for (const auto& [p, points] : placed.parts)
        if (layers.reads(p)) {
            checkCoordinates(file, p.where, points, metres);
            chains[{p.group, p.layer}].push_back({points, p.name, p.where, p.order});
        }
    for (auto& [key, parts] : chains)
        for (auto& chain :
             joinChains(file, std::move(parts), "put the branches on different layers"))
            all.push_back(std::move(chain));
    if (all.empty())
        refuseEmpty(file, scan, layers);
    std::stable_sort(all.begin(), all.end(),
                     [](const auto& a, const auto& b) { return a.order < b.order; });
    return finishRails(file, std::move(all), metres);
}

} // namespace netsculpt::io
