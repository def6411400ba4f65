// The inspector on the left: the piece selected (or under the mouse), the rails and the report
// summary. Every edit executes a command through the interaction layer (undoable, journaled).

#include "Panels.h"

#include "App.h"
#include "TypedValue.h"

#include "model/Compiler.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <cmath>
#include <cstdio>
#include <optional>

namespace netsculpt::studio {

namespace {

constexpr ImGuiInputTextFlags kOnEnter = ImGuiInputTextFlags_EnterReturnsTrue;

bool editDouble(const char* label, double value, double& out, const char* format = "%.4g") {
    out = value;
    const bool entered = ImGui::InputDouble(label, &out, 0, 0, format, kOnEnter);
    if (entered && isEdit(value, out, format)) return true;
    out = value; // Enter on the shown (rounded) text leaves the value as it is
    return false;
}

std::string railLabel(const Sculpture& s, RailId id) {
    return s.hasRail(id) ? toString(id) + " (" + s.rail(id).name + ")" : toString(id);
}

/// Where a rail edge's column 0 is on its rail, "rail 1 (crown) at t = 0.25": a split part's
/// edge keeps its parent's start and counts its columns from its offset.
std::string edgeLabel(const Sculpture& s, const RailEdge& edge) {
    if (!s.hasRail(edge.rail))
        return toString(edge.rail);
    const double t = s.rail(edge.rail).curve().normalizedPosition(railPosition(edge, 0));
    char at[32];
    std::snprintf(at, sizeof at, " at t = %.4g", t);
    return railLabel(s, edge.rail) + at;
}

/// A field for an optional number, blank for none (a breaking load): true and `out` when Enter
/// asks for another value; text that is not a number is said on the status line.
bool editOptional(App& app, const char* label, std::optional<double> value,
                  std::optional<double>& out, const char* format = "%.4g") {
    out = value;
    char shown[48] = "";
    if (value)
        std::snprintf(shown, sizeof shown, format, *value);
    std::string text = shown;
    if (!ImGui::InputTextWithHint(label, "none", &text, kOnEnter))
        return false;
    const TypedOptional typed = readOptional(text, value, format);
    if (!typed.error.empty())
        app.notify(std::string(label) + ": " + typed.error, true);
    if (!typed.edit)
        return false;
    out = typed.value;
    return true;
}

/// The least safety factor over the pieces with a breaking load, and how many have none.
void drawStrength(const nlohmann::json& r) {
    const nlohmann::json least = r.value("min_safety_factor", nlohmann::json());
    if (least.is_number()) {
        const double factor = least.get<double>();
        const int piece = r["min_safety_factor_at"].value("piece", 0);
        if (factor < 1)
            ImGui::TextColored(ImVec4(0.95f, 0.45f, 0.3f, 1),
                               "safety factor %.3g (piece %d): below 1", factor, piece);
        else
            ImGui::Text("least safety factor %.3g (piece %d)", factor, piece);
    }
    const std::size_t unchecked =
        r.value("pieces_without_breaking_load", nlohmann::json::array()).size();
    if (unchecked > 0)
        ImGui::TextDisabled("%zu piece%s without a breaking load: not checked", unchecked,
                            unchecked == 1 ? "" : "s");
}

double magnitude(const nlohmann::json& v) {
    if (v.is_object()) return std::hypot(v.value("x", 0.0), v.value("y", 0.0), v.value("z", 0.0));
    if (v.is_array() && v.size() == 3) return std::hypot(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
    return 0;
}

} // namespace

void Panels::drawInspector(App& app) {
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + 8, vp->Pos.y + menuHeight_ + 8));
    ImGui::SetNextWindowSizeConstraints(ImVec2(kLeftWidth, 0), ImVec2(kLeftWidth, vp->Size.y - menuHeight_ - 60));
    ImGui::SetNextWindowBgAlpha(0.85f);
    if (!ImGui::Begin("Inspector", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_AlwaysAutoResize |
                                                ImGuiWindowFlags_NoSavedSettings)) {
        ImGui::End();
        return;
    }
    const Interaction& ui = app.interaction();
    const PieceId shown = ui.selectedPiece() ? ui.selectedPiece() : ui.hoveredPiece();
    if (ImGui::CollapsingHeader("Piece", ImGuiTreeNodeFlags_DefaultOpen)) {
        if (shown && app.document().sculpture().hasPiece(shown)) drawPiece(app, shown);
        else ImGui::TextDisabled("Click a net to select it.");
    }
    if (ImGui::CollapsingHeader("Rails")) drawRails(app);
    if (ImGui::CollapsingHeader("Report", ImGuiTreeNodeFlags_DefaultOpen)) drawReport(app);
    ImGui::End();
}

void Panels::drawPiece(App& app, PieceId id) {
    Interaction& ui = app.interaction();
    const Sculpture& s = app.document().sculpture();
    const Piece p = s.piece(id); // a copy: a command below may replace the sculpture
    ImGui::PushID(int(id.value));
    ImGui::PushItemWidth(140);
    ImGui::Text("%s%s", toString(id).c_str(), ui.selectedPiece() == id ? "" : "  (under the mouse)");

    std::string name = p.name;
    if (ImGui::InputText("name", &name, kOnEnter) && name != p.name) ui.execute(RenamePieceCommand{id, name});

    int rows = p.rows;
    if (ImGui::InputInt("rows", &rows, 1, 10, kOnEnter) && rows != p.rows) ui.execute(SetRowsCommand{id, rows});
    if (p.onRail() || p.parentTop().whole) {
        int columns = p.columns;
        if (ImGui::InputInt("columns", &columns, 1, 10, kOnEnter) && columns != p.columns)
            ui.execute(SetColumnsCommand{id, columns});
    } else {
        ImGui::Text("columns %d (a split part)", p.columns);
    }
    if (!p.onRail() && p.parentTop().whole) {
        const Gear gear = p.parentTop().gear;
        if (ImGui::BeginCombo("gear", toString(gear).c_str())) {
            for (Gear g : allowedGears())
                if (ImGui::Selectable(toString(g).c_str(), g == gear) && g != gear) ui.execute(SetGearCommand{id, g});
            ImGui::EndCombo();
        }
    }
    ImGui::TextDisabled("%s, %d knots", p.closed ? "closed tube" : "open sheet", p.rows * p.columns);
    if (p.onRail())
        ImGui::TextDisabled("top: %s", edgeLabel(s, p.railTop()).c_str());
    else
        ImGui::TextDisabled("top: below %s, gear %s", toString(p.parentTop().parents.front()).c_str(),
                            toString(p.parentTop().gear).c_str());
    if (p.bottom) {
        ImGui::TextDisabled("bottom: %s", edgeLabel(s, *p.bottom).c_str());
        if (ImGui::SmallButton("disconnect")) ui.execute(DisconnectCommand{id});
    }
    const PieceId left = s.leftPartner(id), right = s.rightPartner(id);
    if (left || right)
        ImGui::TextDisabled("seams: %s%s%s", left ? ("left " + toString(left)).c_str() : "",
                            left && right ? ", " : "",
                            right ? ("right " + toString(right)).c_str() : "");

    // Bar lengths: by column (first, last) or by row (top, last row).
    const bool byRow = p.bar.axis == BarAxis::Row;
    const int lastIndex = byRow ? p.rows - 1 : p.columns - 1;
    const double first = p.bar.at(0), last = p.bar.at(lastIndex);
    const bool seamed = s.leftPartner(id) || s.rightPartner(id);
    double value = 0;
    if (first == last && !seamed && !byRow) {
        if (editDouble("bar (m)", first, value)) ui.execute(SetBarLengthCommand{id, std::nullopt, std::nullopt, value});
    } else {
        auto cmd = [&](int index, double length) {
            return byRow ? SetBarLengthCommand{id, std::nullopt, index, length}
                         : SetBarLengthCommand{id, index, std::nullopt, length};
        };
        if (editDouble(byRow ? "bar top (m)" : "bar first (m)", first, value)) ui.execute(cmd(0, value));
        if (editDouble(byRow ? "bar last row (m)" : "bar last (m)", last, value)) ui.execute(cmd(lastIndex, value));
    }

    if (ImGui::TreeNode("material")) {
        Material m = p.material;
        const Material before = m;
        editDouble("EA (N)", before.stiffness, m.stiffness);
        editDouble("compression ratio", before.compressionRatio, m.compressionRatio);
        editDouble("knot mass (kg)", before.knotMass, m.knotMass);
        editDouble("rope (kg/m)", before.linearDensity, m.linearDensity);
        editOptional(app, "breaking load (N)", before.breakingLoad, m.breakingLoad);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("The load at which a bar breaks, as knotted (with the knots' loss of "
                              "strength).\nBlank: none, and the report checks no strength.");
        if (!(m == before)) ui.execute(SetMaterialCommand{id, m});
        ImGui::TreePop();
    }

    // The colour is applied once the mouse is released (one command per pick, not per drag step).
    if (colourPiece_ != id || !colourPending_) {
        colourPiece_ = id;
        colour_[0] = float(p.colour.r), colour_[1] = float(p.colour.g), colour_[2] = float(p.colour.b);
    }
    if (ImGui::ColorEdit3("colour", colour_, ImGuiColorEditFlags_NoInputs)) colourPending_ = true;
    if (colourPending_ && !ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
        colourPending_ = false;
        ui.execute(SetColourCommand{id, Colour{colour_[0], colour_[1], colour_[2]}});
    }
    if (ImGui::Button("remove (with the pieces below)")) ui.execute(RemovePieceCommand{id});
    ImGui::PopItemWidth();
    ImGui::PopID();
}

void Panels::drawRails(App& app) {
    Interaction& ui = app.interaction();
    const Sculpture& s = app.document().sculpture();
    if (s.rails.empty()) ImGui::TextDisabled("No rails: import some (File > Import rails).");
    for (const auto& [id, rail] : s.rails) {
        ImGui::PushID(int(id.value));
        std::string name = rail.name;
        ImGui::SetNextItemWidth(120);
        const RailId railId = id;
        const std::size_t users = s.piecesOnRail(id).size();
        const double length = rail.curve().length();
        const bool closed = rail.curve().closed();
        if (ImGui::InputText("##name", &name, kOnEnter) && name != rail.name) {
            ui.execute(RenameRailCommand{railId, name});
            ImGui::PopID();
            break; // the rails changed under the loop
        }
        ImGui::SameLine();
        ImGui::TextDisabled("%s %.2f m, %zu piece%s", closed ? "closed" : "open", length, users, users == 1 ? "" : "s");
        ImGui::PopID();
    }
}

void Panels::drawReport(App& app) {
    const nlohmann::json* report = app.report();
    if (!report) {
        ImGui::TextDisabled("No report yet.");
        return;
    }
    try {
        const nlohmann::json& r = *report;
        ImGui::Text("rope length   %.2f m", r.value("rope_length", 0.0));
        ImGui::Text("mass          %.3f kg", r.value("total_mass", 0.0));
        ImGui::Text("max tension   %.2f N", r.value("max_tension", 0.0));
        drawStrength(r);
        double load = 0;
        std::string where = "-";
        for (const auto& rail : r.value("rails", nlohmann::json::array())) {
            const double m = magnitude(rail.value("reaction", nlohmann::json()));
            if (m > load) load = m, where = rail.value("name", std::string());
        }
        ImGui::Text("largest rail load %.2f N (%s)", load, where.c_str());
        ImGui::TextDisabled("%zu slack bars", r.value("slack_bars", std::size_t{0}));
        if (const auto over = r.value("overstretched_bars", std::size_t{0});
            over > 0 && r.value("relaxed", false))
            ImGui::TextColored(ImVec4(0.95f, 0.45f, 0.3f, 1),
                               "%zu bars stretched > %.0f %%: check the design", over,
                               100 * r.value("overstretch_limit", 0.0));
        // The basis the numbers above were computed on (not the live state now: the report is
        // recomputed at most twice a second while a relaxation runs).
        switch (app.reportBasis()) {
        case App::ReportBasis::Relaxed: ImGui::TextDisabled("relaxed shape"); break;
        case App::ReportBasis::Preview:
            ImGui::TextColored(ImVec4(0.95f, 0.75f, 0.3f, 1), "preview forces, x%.2g stiffness", app.reportPreviewScale());
            break;
        case App::ReportBasis::NotRelaxed:
            ImGui::TextColored(ImVec4(0.95f, 0.75f, 0.3f, 1), "not relaxed: forces are not final (Refine)");
            break;
        }
    } catch (const nlohmann::json::exception& e) {
        ImGui::TextDisabled("report: %s", e.what());
    }
}

} // namespace netsculpt::studio
