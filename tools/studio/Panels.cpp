#include "Panels.h"

#include "App.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <cfloat>
#include <cmath>
#include <cstdio>

namespace netsculpt::studio {

namespace {

const char* actionTitle(FileAction a) {
    switch (a) {
    case FileAction::New: return "New sculpture";
    case FileAction::Open: return "Open journal or snapshot (.netj, .nets)";
    case FileAction::Save: return "Save journal";
    case FileAction::SaveAs: return "Save journal as";
    case FileAction::ImportRails: return "Import rails (.dxf, .obj, .csv)";
    case FileAction::Export: return "Export (.csv .obj .ply .glb .json .svg .png)";
    case FileAction::RunScript: return "Run Lua script";
    case FileAction::Screenshot: return "Screenshot (.png)";
    case FileAction::Quit: return "Quit";
    }
    return "";
}

const char* shortcut(Mode m) {
    switch (m) {
    case Mode::View: return "V / 1";
    case Mode::NewNet: return "N / 2";
    case Mode::Divide: return "D / 3";
    case Mode::Rows: return "R / 4";
    case Mode::Columns: return "C / 5";
    case Mode::BarLength: return "B / 6";
    case Mode::Connect: return "J / 7";
    }
    return "";
}

const char* modeHint(Mode m) {
    switch (m) {
    case Mode::View: return "Drag to orbit, right-drag to pan, wheel to zoom, click a net to select it.";
    case Mode::NewNet: return "Click a sphere on a rail or under a last row to hang a new net there.";
    case Mode::Divide:
        return "Click a top knot to split the piece at that column (point at a piece without "
               "spheres to see why it cannot be split).";
    case Mode::Rows: return "Drag a sphere down to add rows, up to remove them (8 px per row).";
    case Mode::Columns: return "Drag up for more columns (on a rail) or a larger gear (below a piece).";
    case Mode::BarLength: return "Drag up for shorter bars, down for longer (seam partners follow).";
    case Mode::Connect: return "Drag a last-row sphere onto a rail sphere to connect it there.";
    }
    return "";
}

/// The questions' actions, done by the App.
class AppFiles : public FileActions {
  public:
    explicit AppFiles(App& app) : app_(app) {}
    bool isClean() const override { return app_.document().isClean(); }
    std::optional<std::filesystem::path> currentPath() const override { return app_.currentPath(); }
    bool save(const std::filesystem::path& path) override { return app_.saveJournal(path); }
    void act(FileAction action) override {
        if (action == FileAction::New) app_.newDocument();
        else if (action == FileAction::Quit) app_.quit();
    }
    void act(FileAction action, const std::string& path) override {
        switch (action) {
        case FileAction::Open: app_.openJournal(path); break;
        case FileAction::ImportRails: app_.importRails(path); break;
        case FileAction::Export: app_.exportTo(path); break;
        case FileAction::RunScript: app_.runScript(path); break;
        case FileAction::Screenshot: app_.takeScreenshot(path); break;
        default: break;
        }
    }

  private:
    App& app_;
};

} // namespace

void Panels::request(FileAction action, App& app) {
    AppFiles files(app);
    questions_.request(action, files);
}

void Panels::draw(App& app) {
    drawMenu(app);
    drawToolbar(app);
    drawInspector(app);
    drawSolver(app);
    drawStatus(app);
    drawDialogs(app);
}

void Panels::drawMenu(App& app) {
    if (!ImGui::BeginMainMenuBar()) return;
    menuHeight_ = ImGui::GetWindowSize().y;
    if (ImGui::BeginMenu("File")) {
        if (ImGui::MenuItem("New")) request(FileAction::New, app);
        if (ImGui::MenuItem("Open journal...", "Ctrl+O")) request(FileAction::Open, app);
        if (ImGui::MenuItem("Save journal", "Ctrl+S")) request(FileAction::Save, app);
        if (ImGui::MenuItem("Save journal as...", "Ctrl+Shift+S")) request(FileAction::SaveAs, app);
        ImGui::Separator();
        if (ImGui::MenuItem("Run Lua script...", nullptr, false, app.canRunScripts())) request(FileAction::RunScript, app);
        if (ImGui::MenuItem("Import rails...")) request(FileAction::ImportRails, app);
        if (ImGui::MenuItem("Export...")) request(FileAction::Export, app);
        if (ImGui::MenuItem("Screenshot...", "F12")) request(FileAction::Screenshot, app);
        ImGui::Separator();
        if (ImGui::MenuItem("Quit", "Ctrl+Q")) request(FileAction::Quit, app);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Edit")) {
        if (ImGui::MenuItem("Undo", "Ctrl+Z", false, app.document().canUndo())) app.interaction().undo();
        if (ImGui::MenuItem("Redo", "Ctrl+Shift+Z", false, app.document().canRedo())) app.interaction().redo();
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("View")) {
        if (ImGui::MenuItem("Frame all", "Home")) app.interaction().frameAll();
        if (ImGui::MenuItem("Top", "T")) app.camera().setPreset(ViewPreset::Top);
        if (ImGui::MenuItem("Front", "F")) app.camera().setPreset(ViewPreset::Front);
        if (ImGui::MenuItem("Side", "S")) app.camera().setPreset(ViewPreset::Side);
        if (ImGui::MenuItem("Perspective", "P")) app.camera().setPreset(ViewPreset::Perspective);
        ImGui::Separator();
        if (ImGui::MenuItem("Colour by piece", nullptr, app.colourBy() == ColourBy::Piece)) app.setColourBy(ColourBy::Piece);
        if (ImGui::MenuItem("Colour by tension", nullptr, app.colourBy() == ColourBy::Tension)) app.setColourBy(ColourBy::Tension);
        ImGui::EndMenu();
    }
    const std::string title = (app.currentPath() ? app.currentPath()->filename().string() : std::string("untitled")) +
                              (app.document().isClean() ? "" : " *");
    ImGui::SameLine(ImGui::GetWindowWidth() - ImGui::CalcTextSize(title.c_str()).x - 16);
    ImGui::TextDisabled("%s", title.c_str());
    ImGui::EndMainMenuBar();
}

void Panels::drawToolbar(App& app) {
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + kLeftWidth + 16, vp->Pos.y + menuHeight_ + 8));
    ImGui::SetNextWindowBgAlpha(0.85f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                   ImGuiWindowFlags_NoMove;
    if (ImGui::Begin("##toolbar", nullptr, flags)) {
        toolbarRight_ = ImGui::GetWindowPos().x + ImGui::GetWindowSize().x;
        toolbarBottom_ = ImGui::GetWindowPos().y + ImGui::GetWindowSize().y;
        Interaction& ui = app.interaction();
        for (Mode m : kAllModes) {
            const bool active = ui.mode() == m;
            if (active) ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyleColorVec4(ImGuiCol_ButtonActive));
            const std::string label(modeName(m));
            if (ImGui::Button(label.c_str())) ui.setMode(m);
            if (active) ImGui::PopStyleColor();
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s  (%s)", modeHint(m), shortcut(m));
            ImGui::SameLine();
        }
        ImGui::TextDisabled("|");
        ImGui::SameLine();
        if (ImGui::Button("undo")) ui.undo();
        ImGui::SameLine();
        if (ImGui::Button("redo")) ui.redo();
        ImGui::SameLine();
        if (ImGui::Button("refine")) app.refine();
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("Relax at the material's stiffness until the residual is below 1e-6");
    }
    ImGui::End();
}

void Panels::drawSolver(App& app) {
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    const float left = vp->Pos.x + vp->Size.x - kRightWidth - 8;
    const float top = toolbarRight_ + 8 > left ? toolbarBottom_ + 8 : vp->Pos.y + menuHeight_ + 8;
    ImGui::SetNextWindowPos(ImVec2(left, top));
    ImGui::SetNextWindowSize(ImVec2(kRightWidth, 0));
    ImGui::SetNextWindowBgAlpha(0.85f);
    if (ImGui::Begin("Solver", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                            ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings)) {
        const MassSpringSystem& sys = app.document().compiled().system;
        ImGui::Text("%zu knots, %zu bars", sys.knotCount(), sys.barCount());
        bool live = app.liveEnabled();
        if (ImGui::Checkbox("live relaxation", &live)) app.setLiveEnabled(live);
        bool autoRefine = app.autoRefine();
        ImGui::SameLine();
        if (ImGui::Checkbox("then refine", &autoRefine)) app.setAutoRefine(autoRefine);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("When the soft preview has settled, relax at the material's stiffness\n"
                              "(the report's forces are only right then)");
        if (const auto s = app.liveState()) {
            const char* phase = s->phase == LivePhase::Refine ? "refine" : "preview";
            if (s->running) ImGui::Text("%s: relaxing...", phase);
            else if (s->stopReason == "error") ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "%s: %s", phase, s->error.c_str());
            else ImGui::Text("%s: %s", phase, s->stopReason.c_str());
            ImGui::Text("residual %.3g at stiffness x%.3g", s->residual, s->stiffnessScale);
            ImGui::Text("%lld steps, %.2f s", static_cast<long long>(s->steps), s->seconds);
        } else if (app.document().isRelaxed()) {
            ImGui::TextDisabled("relaxed at the material's stiffness");
        } else {
            ImGui::TextDisabled(live ? "waiting for the first shape" : "showing the initial geometry");
        }
        const auto& history = app.residualHistory();
        if (!history.empty())
            ImGui::PlotLines("##residual", history.data(), int(history.size()), 0, "log10 residual", FLT_MAX, FLT_MAX,
                             ImVec2(kRightWidth - 20, 60));
        if (ImGui::Button("Refine")) app.refine();
        ImGui::SameLine();
        ImGui::TextDisabled("%.0f fps", app.framesPerSecond());
        if (app.colourBy() == ColourBy::Tension)
            drawTensionScale(app.maxTension());
    }
    ImGui::End();
}

/// The bars' tension colours as a scale: slack (grey), then 0 to the largest tension.
void Panels::drawTensionScale(double maxTension) {
    const auto colour = [](const std::array<float, 3>& c) {
        return ImGui::GetColorU32(ImVec4(c[0], c[1], c[2], 1));
    };
    ImDrawList* draw = ImGui::GetWindowDrawList();
    const ImVec2 at = ImGui::GetCursorScreenPos();
    const float height = 12, slack = 44, width = kRightWidth - 20 - slack - 6;
    draw->AddRectFilled(at, ImVec2(at.x + slack, at.y + height), colour(tensionColour(0, 1)));
    constexpr int kSteps = 24;
    for (int i = 0; i < kSteps; ++i) {
        const float x0 = at.x + slack + 6 + width * float(i) / kSteps;
        const float x1 = at.x + slack + 6 + width * float(i + 1) / kSteps;
        const ImU32 left = colour(tensionColour(double(i) / kSteps + 1e-9, 1));
        const ImU32 right = colour(tensionColour(double(i + 1) / kSteps, 1));
        draw->AddRectFilledMultiColor(ImVec2(x0, at.y), ImVec2(x1, at.y + height), left, right,
                                      right, left);
    }
    ImGui::Dummy(ImVec2(kRightWidth - 20, height));
    const float left = ImGui::GetCursorPosX();
    ImGui::TextDisabled("slack");
    ImGui::SameLine(left + slack + 6);
    ImGui::TextDisabled("0 N");
    char largest[48];
    std::snprintf(largest, sizeof largest, "%.4g N (largest)", maxTension);
    ImGui::SameLine(left + slack + 6 + width - ImGui::CalcTextSize(largest).x);
    ImGui::TextDisabled("%s", largest);
}

void Panels::drawStatus(App& app) {
    // Along the window's bottom edge, as tall as its text: a long message (a refusal with what
    // to do, an export's warning) wraps instead of running off the window's right edge.
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x, vp->Pos.y + vp->Size.y), ImGuiCond_Always,
                            ImVec2(0, 1));
    ImGui::SetNextWindowSize(ImVec2(vp->Size.x, 0)); // height 0: fitted to the text
    ImGui::SetNextWindowBgAlpha(0.7f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoSavedSettings |
                                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoMove;
    if (ImGui::Begin("##status", nullptr, flags)) {
        const Interaction& ui = app.interaction();
        const std::string mode(modeName(ui.mode()));
        ImGui::Text("[%s]", mode.c_str());
        ImGui::SameLine();
        const bool error = !app.notice().empty() ? app.noticeIsError() : ui.messageIsError();
        const std::string& text = !app.notice().empty() ? app.notice() : ui.message();
        const ImVec4 colour =
            error ? ImVec4(1, 0.45f, 0.35f, 1) : ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled);
        ImGui::PushStyleColor(ImGuiCol_Text, colour);
        ImGui::TextWrapped("%s", text.empty() ? modeHint(ui.mode()) : text.c_str());
        ImGui::PopStyleColor();
    }
    ImGui::End();
}

void Panels::drawDialogs(App& app) {
    if (app.restorePending()) ImGui::OpenPopup("Restore session?");
    if (ImGui::BeginPopupModal("Restore session?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::Text("The last session's work is in\n%s", app.sessionJournal().string().c_str());
        if (ImGui::Button("Restore it")) {
            app.answerRestore(true);
            ImGui::CloseCurrentPopup();
        }
        ImGui::SameLine();
        if (ImGui::Button("Start afresh")) {
            app.answerRestore(false);
            ImGui::CloseCurrentPopup();
        }
        ImGui::EndPopup();
    }

    drawUnsaved(app);
    drawPath(app);
}

void Panels::drawUnsaved(App& app) {
    if (questions_.takeOpenedUnsaved()) ImGui::OpenPopup("Unsaved changes");
    if (!ImGui::BeginPopupModal("Unsaved changes", nullptr, ImGuiWindowFlags_AlwaysAutoResize))
        return;
    ImGui::Text("This sculpture has changes that are not saved.");
    std::optional<UnsavedAnswer> answer;
    if (ImGui::Button("Save")) answer = UnsavedAnswer::Save;
    ImGui::SameLine();
    if (ImGui::Button("Discard")) answer = UnsavedAnswer::Discard;
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) answer = UnsavedAnswer::Cancel;
    if (answer) {
        ImGui::CloseCurrentPopup();
        AppFiles files(app);
        questions_.answerUnsaved(*answer, files);
    }
    ImGui::EndPopup();
}

void Panels::drawPath(App& app) {
    if (questions_.takeOpenedPath()) ImGui::OpenPopup("File");
    if (!ImGui::BeginPopupModal("File", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
    ImGui::Text("%s", actionTitle(questions_.askingPath().value_or(FileAction::Open)));
    if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
    ImGui::SetNextItemWidth(460);
    std::string& path = questions_.path();
    const bool enter = ImGui::InputText("##path", &path,
                                        ImGuiInputTextFlags_EnterReturnsTrue |
                                            ImGuiInputTextFlags_AutoSelectAll);
    if ((ImGui::Button("OK") || enter) && !path.empty()) {
        ImGui::CloseCurrentPopup();
        AppFiles files(app);
        questions_.answerPath(std::string(path), files);
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) {
        ImGui::CloseCurrentPopup();
        questions_.cancelPath();
    }
    ImGui::EndPopup();
}

} // namespace netsculpt::studio
