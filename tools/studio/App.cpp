// The window and the frame loop: GLFW callbacks and --play events both go through dispatch().

#include "App.h"

#include "Gl.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <imgui_internal.h> // the windows of the last frame (panelCovers)

#include "interaction/DemoScenes.h"
#include "model/Error.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <thread>

namespace netsculpt::studio {

static_assert(keys::Escape == GLFW_KEY_ESCAPE && keys::Home == GLFW_KEY_HOME && keys::F1 == GLFW_KEY_F1 &&
                  keys::Delete == GLFW_KEY_DELETE && keys::Up == GLFW_KEY_UP && 'A' == GLFW_KEY_A,
              "interaction key codes are GLFW's");

namespace {

/// The live relaxer's nice value when the frames are drawn on the CPU: its share of a core that a
/// frame also wants is about a tenth.
constexpr int kRelaxerNicenessBesideSoftwareRenderer = 10;

/// s between two refreshes of the primary display (1/60 when it does not say).
double displayFramePeriod() {
    const GLFWvidmode* mode = glfwGetPrimaryMonitor() ? glfwGetVideoMode(glfwGetPrimaryMonitor()) : nullptr;
    return mode && mode->refreshRate > 0 ? 1.0 / mode->refreshRate : 1.0 / 60;
}

/// Mesa's software rasterizers (llvmpipe, softpipe), which pay for every line and every pixel.
bool softwareRenderer() {
    const char* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    return name && (std::strstr(name, "llvmpipe") || std::strstr(name, "softpipe"));
}

App& appOf(GLFWwindow* window) { return *static_cast<App*>(glfwGetWindowUserPointer(window)); }

Modifiers modsOf(int mods) {
    return Modifiers{(mods & GLFW_MOD_SHIFT) != 0, (mods & GLFW_MOD_CONTROL) != 0, (mods & GLFW_MOD_ALT) != 0};
}

MouseButton buttonOf(int button) {
    return button == GLFW_MOUSE_BUTTON_RIGHT ? MouseButton::Right
           : button == GLFW_MOUSE_BUTTON_MIDDLE ? MouseButton::Middle
                                                : MouseButton::Left;
}

/// Window coordinates to framebuffer pixels (they differ on high-DPI screens).
double framebufferScale(GLFWwindow* window) {
    int w = 0, fw = 0, h = 0, fh = 0;
    glfwGetWindowSize(window, &w, &h);
    glfwGetFramebufferSize(window, &fw, &fh);
    return w > 0 ? double(fw) / w : 1.0;
}

/// Whether a panel drawn in the last frame covers window pixel (x, y): ImGui's own test of the
/// window under the mouse (FindHoveredWindow in imgui.cpp), asked whoever owns the mouse. While
/// a drag that began in the view goes on, ImGui reports no window hovered and does not want the
/// mouse, yet its panels hide the view behind them.
bool panelCovers(double x, double y) {
    const ImGuiContext* context = ImGui::GetCurrentContext();
    if (!context)
        return false;
    const ImVec2 scale = context->IO.DisplayFramebufferScale; // window to framebuffer pixels
    const ImVec2 at(float(x / (scale.x > 0 ? scale.x : 1)), float(y / (scale.y > 0 ? scale.y : 1)));
    for (const ImGuiWindow* window : context->Windows) {
        const bool shown = window->Active && !window->Hidden;
        if (shown && !(window->Flags & ImGuiWindowFlags_NoMouseInputs) &&
            window->OuterRectClipped.Contains(at))
            return true;
    }
    return false;
}

void onCursor(GLFWwindow* w, double x, double y) {
    const double s = framebufferScale(w);
    appOf(w).windowEvent(MouseMove{x * s, y * s});
}
void onButton(GLFWwindow* w, int button, int action, int mods) {
    if (button > GLFW_MOUSE_BUTTON_MIDDLE) return;
    if (action == GLFW_PRESS) appOf(w).windowEvent(MousePress{buttonOf(button), modsOf(mods)});
    else if (action == GLFW_RELEASE) appOf(w).windowEvent(MouseRelease{buttonOf(button), modsOf(mods)});
}
void onScroll(GLFWwindow* w, double, double dy) { appOf(w).windowEvent(Scroll{dy}); }
void onKey(GLFWwindow* w, int key, int, int action, int mods) {
    if (action != GLFW_RELEASE && key != GLFW_KEY_UNKNOWN) appOf(w).windowEvent(KeyPress{key, modsOf(mods)});
}

} // namespace

App::App(StudioOptions options) : options_(std::move(options)) {
    colourBy_ = options_.colourBy == "tension" ? ColourBy::Tension : ColourBy::Piece;
    liveEnabled_ = options_.relax;
    scriptRunner_ = makeScriptRunner();
    if (options_.play) script_ = readEventScript(options_.play->string());
    camera_.setViewport(options_.width, options_.height);
    camera_.frameInset = Panels::kFrameInset;
    doc_ = std::make_unique<Document>();
    interaction_ = std::make_unique<Interaction>(*doc_, camera_);
    LiveRelaxOptions live;
    live.threads = threadsBesideTheFrames();
    live.settleThreads = threadsForSettling();
    live_ = std::make_unique<LiveRelaxer>(live);
}

App::~App() {
    live_.reset(); // stop the worker before the document goes
    shutdownWindow();
}

void App::initWindow() {
    if (!glfwInit()) throw std::runtime_error("cannot initialise GLFW (is there a display? try xvfb-run)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    // Multisampling: 4x on a GPU; off on a software renderer (llvmpipe), where it costs 4x the
    // fill rate, unless --samples asks for it.
    for (int attempt = 0; attempt < 2 && !window_; ++attempt) {
        glfwWindowHint(GLFW_SAMPLES, options_.samples >= 0 ? options_.samples : attempt == 0 ? 4 : 0);
        window_ = glfwCreateWindow(options_.width, options_.height, "netsculpt studio", nullptr, nullptr);
        if (!window_) throw std::runtime_error("cannot open an OpenGL 3.3 core window");
        glfwMakeContextCurrent(window_);
        if (attempt == 0 && softwareRenderer() && options_.samples < 0) {
            glfwDestroyWindow(window_);
            window_ = nullptr;
        }
    }
    glfwSwapInterval(options_.vsync ? 1 : 0);
    if (options_.vsync && softwareRenderer()) framePeriod_ = displayFramePeriod();
    glfwSetWindowUserPointer(window_, this);
    // Ours first: ImGui's backend chains to them after updating its own state.
    glfwSetCursorPosCallback(window_, onCursor);
    glfwSetMouseButtonCallback(window_, onButton);
    glfwSetScrollCallback(window_, onScroll);
    glfwSetKeyCallback(window_, onKey);

    initImGui();
    glEnable(GL_MULTISAMPLE);
    renderer_.init();
    // A software renderer draws with the CPU: runs of short bars that look straight on screen are
    // drawn as one line, and the relaxation gives way to the frames (it gets the CPU they leave).
    if (softwareRenderer()) {
        renderer_.setBarMergeTolerance(NetLineOptions{}.tolerancePixels);
        live_->setNiceness(kRelaxerNicenessBesideSoftwareRenderer);
    }
}

void App::initImGui() {
    // On a software renderer the font is rasterized at its size and every glyph starts on a whole
    // pixel, so the atlas can be sampled without filtering: the same text, and the panels cost a
    // third less to draw there.
    const bool software = softwareRenderer();
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr; // panels are laid out by code; nothing to remember
    ImFontConfig fontConfig;
    if (software) fontConfig.OversampleH = 1, fontConfig.PixelSnapH = true;
    const char* font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
    if (std::filesystem::exists(font)) io.Fonts->AddFontFromFileTTF(font, 15.0f, &fontConfig);
    ImGui::StyleColorsDark();
    ImGuiStyle& style = ImGui::GetStyle();
    style.WindowRounding = 6;
    style.FrameRounding = 4;
    style.GrabRounding = 4;
    style.WindowBorderSize = 0;
    style.AntiAliasedLinesUseTex = !software; // its baked lines need filtering
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
    if (software) sampleFontAtlasUnfiltered();
}

void App::shutdownWindow() {
    if (!window_) return;
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window_);
    window_ = nullptr;
    glfwTerminate();
}

int App::run() {
    buildInitialDocument();
    initWindow();
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window_, &fw, &fh);
    camera_.setViewport(fw, fh);
    interaction_->frameAll();
    fpsWindowStart_ = std::chrono::steady_clock::now();
    auto afterFirstFrame = fpsWindowStart_; // the first frame (shader warm-up) is not measured
    auto frameStart = fpsWindowStart_;
    FrameClock relaxing, still;
    while (!quitRequested_ && !glfwWindowShouldClose(window_)) {
        const bool relaxerRunning = !live_->waitIdle(0); // working, whether or not it has published yet
        const bool settles = isLastFrame() && options_.settleSeconds > 0; // waits: not a frame time
        frame();
        const auto frameEnd = std::chrono::steady_clock::now();
        const double frameSeconds = std::chrono::duration<double>(frameEnd - frameStart).count();
        if (++frameIndex_ == 1) afterFirstFrame = frameEnd;
        else if (!settles) (relaxerRunning ? relaxing : still).add(frameSeconds);
        frameStart = frameEnd;
        if (options_.exitAfterFrames > 0 && frameIndex_ >= options_.exitAfterFrames) break;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - afterFirstFrame).count();
    std::printf("netsculpt-studio: %lld frames, %.1f fps, %zu knots\n", frameIndex_,
                seconds > 0 ? double(frameIndex_ - 1) / seconds : 0.0, doc_->compiled().system.knotCount());
    std::printf("netsculpt-studio: %.1f fps while relaxing (%lld frames, slowest %.0f ms), %.1f fps still (%lld "
                "frames, slowest %.0f ms)\n",
                relaxing.framesPerSecond(), relaxing.frames, 1e3 * relaxing.longest, still.framesPerSecond(),
                still.frames, 1e3 * still.longest);
    if (liveState_)
        std::printf("netsculpt-studio: relaxation %s, residual %.3g at stiffness x%.3g\n",
                    liveState_->running ? "running" : liveState_->stopReason.c_str(), liveState_->residual,
                    liveState_->stiffnessScale);
    return 0;
}

void App::paceToDisplay() {
    // A software renderer's swap does not wait for the display: frames keep to the display's
    // period here, on a fixed schedule (a late wake-up is made up by the next frame), and the CPU
    // left goes to the relaxation.
    if (framePeriod_ <= 0) return;
    const auto now = std::chrono::steady_clock::now();
    nextFrameDue_ += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(framePeriod_));
    if (nextFrameDue_ < now) nextFrameDue_ = now; // behind: start the schedule again from here
    std::this_thread::sleep_until(nextFrameDue_);
}

void App::sampleFontAtlasUnfiltered() {
    ImGui_ImplOpenGL3_CreateDeviceObjects(); // the atlas texture, which ImGui would make at its first frame
    glBindTexture(GL_TEXTURE_2D, GLuint(reinterpret_cast<std::intptr_t>(ImGui::GetIO().Fonts->TexID)));
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
}

bool App::isLastFrame() const {
    return options_.exitAfterFrames > 0 && frameIndex_ + 1 >= options_.exitAfterFrames;
}

void App::frame() {
    glfwPollEvents();
    if (glfwWindowShouldClose(window_) && !doc_->isClean() && !options_.play && options_.exitAfterFrames < 0) {
        glfwSetWindowShouldClose(window_, GLFW_FALSE); // ask first
        panels_.request(FileAction::Quit, *this);
    }
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window_, &fw, &fh);
    camera_.setViewport(fw, fh);
    playEvents();

    const bool lastFrame = isLastFrame();
    if (lastFrame && options_.settleSeconds > 0) { // let the preview (and the refine after it) finish
        const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(options_.settleSeconds);
        for (int round = 0; round < 4 && std::chrono::steady_clock::now() < until; ++round) {
            syncLive(); // takes the last state; may start the next run
            live_->waitIdle(std::chrono::duration<double>(until - std::chrono::steady_clock::now()).count());
        }
    }
    syncLive();
    if (options_.printHandles && frameIndex_ == 1) printHandles(*options_.printHandles);

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    if (options_.play) { // replayed events drive ImGui's mouse as well
        ImGuiIO& io = ImGui::GetIO();
        io.MousePos = cursorKnown_ ? ImVec2(float(cursorX_), float(cursorY_)) : ImVec2(-FLT_MAX, -FLT_MAX);
        for (int b = 0; b < 3; ++b) io.MouseDown[b] = buttonDown_[b];
    }
    ImGui::NewFrame();
    panels_.draw(*this);
    ImGui::Render();

    renderer_.draw(camera_, buildOverlay());
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (lastFrame && options_.screenshot) pendingScreenshot_ = *options_.screenshot;
    if (pendingScreenshot_) writePendingScreenshot();
    glfwSwapBuffers(window_);
    paceToDisplay();

    ++fpsFrames_;
    const auto now = std::chrono::steady_clock::now();
    const double window = std::chrono::duration<double>(now - fpsWindowStart_).count();
    if (window >= 0.5) {
        fps_ = fpsFrames_ / window;
        fpsFrames_ = 0;
        fpsWindowStart_ = now;
    }
}

void App::playEvents() {
    while (nextStep_ < script_.size() && frameIndex_ >= resumeAtFrame_) {
        const ScriptStep& step = script_[nextStep_++];
        if (const auto* wait = std::get_if<FrameWait>(&step.what)) resumeAtFrame_ = frameIndex_ + wait->frames;
        else dispatch(std::get<InputEvent>(step.what));
    }
}

void App::windowEvent(const InputEvent& event) {
    if (!options_.play) dispatch(event); // a replay is the only input: the real pointer must not interfere
}

void App::dispatch(const InputEvent& event) {
    const ImGuiIO* io = ImGui::GetCurrentContext() ? &ImGui::GetIO() : nullptr;
    const bool uiHasMouse = io && io->WantCaptureMouse;
    Interaction& ui = *interaction_;
    if (const auto* move = std::get_if<MouseMove>(&event)) {
        cursorX_ = move->x, cursorY_ = move->y;
        cursorKnown_ = true;
        ui.setPointerOverPanel(panelCovers(cursorX_, cursorY_));
        ui.handle(event);
    } else if (const auto* press = std::get_if<MousePress>(&event)) {
        buttonDown_[int(press->button)] = true;
        notice_.clear();
        if (!uiHasMouse && !restorePending_) ui.handle(event);
    } else if (const auto* release = std::get_if<MouseRelease>(&event)) {
        buttonDown_[int(release->button)] = false;
        // Always: a gesture that started in the view ends wherever the mouse is; over a panel it
        // drops nothing (the panels of the last frame, as the artist sees them).
        ui.setPointerOverPanel(panelCovers(cursorX_, cursorY_));
        ui.handle(event);
    } else if (std::holds_alternative<Scroll>(event)) {
        if (!uiHasMouse) ui.handle(event);
    } else if (const auto* key = std::get_if<KeyPress>(&event)) {
        if ((io && io->WantTextInput) || restorePending_) return;
        notice_.clear();
        const Modifiers m = key->mods;
        if (m.ctrl && key->key == 'O') return panels_.request(FileAction::Open, *this);
        if (m.ctrl && key->key == 'S') return panels_.request(m.shift ? FileAction::SaveAs : FileAction::Save, *this);
        if (m.ctrl && key->key == 'Q') return panels_.request(FileAction::Quit, *this);
        if (key->key == keys::F1 + 11) return panels_.request(FileAction::Screenshot, *this);
        ui.handle(event);
    }
}

void App::syncLive() {
    Document& doc = *doc_;
    if (interaction_->version() != shownVersion_) {
        shownVersion_ = interaction_->version();
        renderer_.setSculpture(doc.sculpture(), doc.compiled());
        positionsDirty_ = true;
        reportDirty_ = true;
        residualHistory_.clear();
        // A relaxed shape (an opened snapshot, an undo back to one) is already the equilibrium
        // at the material's stiffness: a soft preview would only sag it and refine it back.
        if (liveEnabled_ && !doc.isRelaxed())
            live_->preview(doc.compiled().system, shownVersion_,
                           interaction_->dragged().has_value());
        else live_->cancel(); // a run for the state before would go on for nothing
    }
    if (const auto state = live_->latest(); state && state->sequence != seenSequence_) {
        seenSequence_ = state->sequence;
        liveState_ = state;
        if (state->generation == shownVersion_) {
            if (state->positions.size() == doc.compiled().system.knotCount()) {
                // The next edit warm-starts from the shape shown.
                doc.adoptPositions(state->positions, state->phase == LivePhase::Refine && state->converged);
                positionsDirty_ = true;
                reportDirty_ = true;
            }
            if (state->residual > 0) residualHistory_.push_back(float(std::log10(state->residual)));
            if (residualHistory_.size() > 400) residualHistory_.erase(residualHistory_.begin());
        }
    }
    // Once the soft preview has settled, go on to the material's stiffness (the report's forces
    // are only right there); Newton gets there in a few steps from the preview's shape. Not while
    // a handle is held: the drag's next step would cut the refine short.
    if (autoRefine_ && liveEnabled_ && liveState_ && !liveState_->running && liveState_->converged &&
        liveState_->phase == LivePhase::Preview && liveState_->generation == shownVersion_ &&
        refinedVersion_ != shownVersion_ && !interaction_->dragged()) {
        refinedVersion_ = shownVersion_;
        live_->refine(doc.compiled().system, shownVersion_);
    }
    if (positionsDirty_) {
        renderer_.setPositions(doc.sculpture(), doc.compiled().system, colourBy_);
        interaction_->refresh();
        positionsDirty_ = false;
    }
}

Overlay App::buildOverlay() const {
    Overlay o;
    const Interaction& ui = *interaction_;
    o.highlight = ui.selectedPiece() ? ui.selectedPiece() : ui.hoveredPiece();
    auto colourOf = [](HandleKind kind) -> std::array<float, 4> {
        switch (kind) {
        case HandleKind::RailPoint: return {0.92f, 0.92f, 0.95f, 1};
        case HandleKind::LastRow: return {0.35f, 0.85f, 0.45f, 1};
        case HandleKind::TopKnot: return {0.98f, 0.82f, 0.25f, 1};
        case HandleKind::RowsEnd: return {0.30f, 0.80f, 0.95f, 1};
        case HandleKind::ColumnsEdge: return {0.70f, 0.55f, 0.98f, 1};
        case HandleKind::BarEnd: return {0.98f, 0.60f, 0.25f, 1};
        case HandleKind::ConnectSource: return {0.35f, 0.85f, 0.45f, 1};
        case HandleKind::ConnectTarget: return {0.92f, 0.92f, 0.95f, 1};
        }
        return {1, 1, 1, 1};
    };
    for (const Handle& h : ui.handles())
        o.spheres.push_back({h.position, camera_.worldPerPixels(h.position, h.pixelRadius), colourOf(h.kind)});
    if (ui.hovered() >= 0) {
        const Handle& h = ui.handles()[std::size_t(ui.hovered())];
        o.translucent.push_back({h.position, camera_.worldPerPixels(h.position, h.pixelRadius * 1.8), {1, 0.2f, 0.15f, 0.5f}});
    }
    if (const auto& dragged = ui.dragged(); dragged && dragged->kind == HandleKind::ConnectSource) {
        const Ray ray = camera_.rayAt(ui.cursorX(), ui.cursorY());
        const Vec3 carried = ray.origin + ray.direction * distance(ray.origin, dragged->position);
        o.guides.push_back({dragged->position, carried});
        o.spheres.push_back({carried, camera_.worldPerPixels(carried, dragged->pixelRadius), colourOf(dragged->kind)});
    }
    return o;
}

void App::printHandles(const std::string& mode) {
    Interaction& ui = *interaction_;
    const Mode before = ui.mode();
    for (Mode m : kAllModes)
        if (modeName(m) == mode) ui.setMode(m);
    for (std::size_t i = 0; i < ui.handles().size(); ++i) {
        const Handle& h = ui.handles()[i];
        const ScreenPoint sp = camera_.project(h.position);
        std::printf("handle %zu piece %u rail %u row %d column %d t %.6g at %.1f %.1f%s\n", i, h.piece.value,
                    h.rail.value, h.row, h.column, h.t, sp.x, sp.y, sp.visible ? "" : " (off screen)");
    }
    ui.setMode(before);
}

} // namespace netsculpt::studio
