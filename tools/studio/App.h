#pragma once
// netsculpt-studio: the window, the frame loop and the glue between GLFW, the interaction layer,
// the live relaxer, the renderer and the panels. Window events and replayed events (--play) both
// enter through dispatch(), so a recorded session drives exactly what a user's mouse does.

#include "Panels.h"
#include "Renderer.h"
#include "ScriptRunner.h"
#include "StudioOptions.h"

#include "commands/Document.h"
#include "interaction/EventScript.h"
#include "interaction/Interaction.h"
#include "interaction/LiveRelaxer.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>

struct GLFWwindow;

namespace netsculpt::studio {

/// Frames and their time, for the frame rates printed at exit.
struct FrameClock {
    long long frames = 0;
    double seconds = 0;
    double longest = 0; ///< s, the slowest frame
    void add(double frameSeconds) {
        ++frames, seconds += frameSeconds;
        longest = std::max(longest, frameSeconds);
    }
    double framesPerSecond() const { return seconds > 0 ? double(frames) / seconds : 0.0; }
};

class App {
  public:
    explicit App(StudioOptions options);
    ~App();
    App(const App&) = delete;
    App& operator=(const App&) = delete;

    /// Opens the window and runs until it is closed or --exit-after-frames; returns the exit code.
    int run();

    /// Every input event, from GLFW's callbacks or from the --play file.
    void dispatch(const InputEvent& event);
    /// An event from GLFW's callbacks: dispatched, unless a --play file drives this session.
    void windowEvent(const InputEvent& event);

    // ---- what the panels use ----
    Document& document() { return *doc_; }
    Interaction& interaction() { return *interaction_; }
    Camera& camera() { return camera_; }
    std::shared_ptr<const LiveState> liveState() const { return liveState_; }
    /// The stiffness scale of the shape shown: < 1 while it is a preview.
    double previewScaleShown() const;
    bool liveEnabled() const { return liveEnabled_; }
    void setLiveEnabled(bool on);
    /// Refine automatically when the preview has settled (on by default).
    bool autoRefine() const { return autoRefine_; }
    void setAutoRefine(bool on) { autoRefine_ = on; }
    ColourBy colourBy() const { return colourBy_; }
    void setColourBy(ColourBy c);
    void refine();
    double framesPerSecond() const { return fps_; }
    double maxTension() const { return renderer_.maxTension(); }
    /// What the forces of a report are: the relaxed shape's at the material's stiffness, a
    /// preview shape's at the preview's stiffness, or a shape's that is neither.
    enum class ReportBasis { Relaxed, Preview, NotRelaxed };
    /// The report of the current shape: recomputed at once after an edit (but twice a second
    /// while a drag goes on) and when the relaxation of the current version has ended (its
    /// settled shape's forces), else at most twice a second while the shape moves.
    const nlohmann::json* report();
    /// The basis of the last report() and, for a preview, its stiffness scale.
    ReportBasis reportBasis() const { return reportBasis_; }
    double reportPreviewScale() const { return reportPreviewScale_; }
    const std::vector<float>& residualHistory() const { return residualHistory_; }
    const std::optional<std::filesystem::path>& currentPath() const { return currentPath_; }
    const std::filesystem::path& sessionJournal() const { return sessionPath_; }
    bool canRunScripts() const { return scriptRunner_ != nullptr; }

    // File actions: each reports success or its error through the status line (never throws).
    bool openJournal(const std::filesystem::path& path);
    bool saveJournal(const std::filesystem::path& path);
    bool importRails(const std::filesystem::path& path);
    bool exportTo(const std::filesystem::path& path);
    bool runScript(const std::filesystem::path& path);
    bool takeScreenshot(const std::filesystem::path& path);
    void newDocument();
    /// Answer to the start-up question: restore the previous session's journal or start afresh.
    void answerRestore(bool restore);
    bool restorePending() const { return restorePending_; }
    void quit() { quitRequested_ = true; }
    void notify(const std::string& message, bool error);
    const std::string& notice() const { return notice_; }
    bool noticeIsError() const { return noticeIsError_; }

  private:
    nlohmann::json previewReport() const;
    void initWindow();
    void initImGui();
    void sampleFontAtlasUnfiltered();
    void shutdownWindow();
    void buildInitialDocument();
    void attachSession();
    /// Keeps the session journal's work as NAME.previous.netj before it is journaled afresh;
    /// UserError when the copy cannot be made (then nothing has changed).
    void keepSessionWork();
    void replaceDocument(Document next);
    void frame();
    bool isLastFrame() const; ///< the frame about to be drawn is the last of --exit-after-frames
    void paceToDisplay();
    void playEvents();
    void syncLive();
    Overlay buildOverlay() const;
    void printHandles(const std::string& mode);
    void writePendingScreenshot();

    StudioOptions options_;
    GLFWwindow* window_ = nullptr;
    std::unique_ptr<Document> doc_;
    Camera camera_;
    std::unique_ptr<Interaction> interaction_;
    std::unique_ptr<LiveRelaxer> live_;
    std::unique_ptr<ScriptRunner> scriptRunner_;
    Renderer renderer_;
    Panels panels_;

    std::filesystem::path sessionPath_;
    std::optional<std::filesystem::path> currentPath_;
    bool restorePending_ = false;
    bool quitRequested_ = false;
    std::optional<std::filesystem::path> pendingScreenshot_; ///< written after this frame is drawn

    std::vector<ScriptStep> script_;
    std::size_t nextStep_ = 0;
    long long resumeAtFrame_ = 0;
    long long frameIndex_ = 0;
    double cursorX_ = 0, cursorY_ = 0;
    bool cursorKnown_ = false; ///< no MouseMove yet: ImGui is told the mouse is away
    bool buttonDown_[3] = {false, false, false};

    std::uint64_t shownVersion_ = 0;     ///< interaction version the renderer and relaxer have
    std::uint64_t seenSequence_ = 0;     ///< last LiveState sequence taken
    std::shared_ptr<const LiveState> liveState_;
    bool liveEnabled_ = true;
    bool autoRefine_ = true;
    std::uint64_t refinedVersion_ = 0; ///< the version auto-refine last ran for
    ColourBy colourBy_ = ColourBy::Piece;
    bool positionsDirty_ = true;
    std::vector<float> residualHistory_;

    nlohmann::json report_;
    bool reportValid_ = false;
    bool reportDirty_ = true;
    std::uint64_t reportVersion_ = 0; ///< the interaction's version the report was made for
    std::chrono::steady_clock::time_point reportTime_{};
    ReportBasis reportBasis_ = ReportBasis::NotRelaxed;
    double reportPreviewScale_ = 1;

    std::string notice_;
    bool noticeIsError_ = false;
    double framePeriod_ = 0; ///< s; > 0: frames are paced to the display here (its swap does not wait)
    std::chrono::steady_clock::time_point nextFrameDue_{}; ///< when the next frame may be shown
    double fps_ = 0;
    std::chrono::steady_clock::time_point fpsWindowStart_{};
    int fpsFrames_ = 0;
};

} // namespace netsculpt::studio
