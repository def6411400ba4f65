// Crash safety: a child process appends commands to a journal and is killed with SIGKILL at a
// random moment; reopening recovers every acknowledged command and nothing that was not issued.

#include "CommandTestSupport.h"

#include <chrono>
#include <random>
#include <thread>

#include <csignal>
#include <sys/wait.h>

using namespace netsculpt;
using namespace netsculpt::test;

namespace {

/// The k-th action of the child (a deterministic function of k, always valid after k - 1).
void applyAction(Document& doc, std::uint64_t k) {
    if (k == 0) {
        doc.execute(AddRailCommand{"top", polygonRail(12, 1.0, 3.0)});
        return;
    }
    if (k == 1) {
        doc.execute(attach(1, 12, 4, 0.4));
        return;
    }
    const double f = double(k % 97) / 97.0;
    switch ((k - 2) % 8) {
    case 0: doc.execute(SetRowsCommand{PieceId(1), 3 + int(k % 6)}); break;
    case 1: doc.execute(SetColourCommand{PieceId(1), Colour{f, 1 - f, 0.5}}); break;
    case 2: doc.execute(SetBarLengthCommand{PieceId(1), std::nullopt, std::nullopt, 0.4 + f * 0.1}); break;
    case 3: doc.execute(RenamePieceCommand{PieceId(1), "name " + std::to_string(k)}); break;
    case 4: doc.undo(); break;
    case 5: doc.redo(); break;
    case 6: doc.execute(SetGravityCommand{Vec3{f, 0, -9.81}}); break;
    default: {
        Material m;
        m.stiffness = 1e5 + double(k);
        doc.execute(SetMaterialCommand{PieceId(1), m});
    }
    }
}

[[noreturn]] void runChild(const std::filesystem::path& path, std::uint64_t start, int ackFd) {
    try {
        Document doc = start == 0 ? Document() : Document::open(path);
        if (start == 0) doc.attachJournal(path);
        for (std::uint64_t k = start; k < start + 1000000; ++k) {
            applyAction(doc, k);
            const std::uint64_t acknowledged = k + 1; // entries in the journal, all synced
            if (::write(ackFd, &acknowledged, sizeof acknowledged) != sizeof acknowledged) ::_exit(4);
        }
    } catch (...) {
        ::_exit(3);
    }
    ::_exit(0);
}

} // namespace

TEST_CASE("a journal writer killed at random moments loses nothing it acknowledged", "[crash]") {
    TempDir dir(false); // a real file system, where fdatasync does real work
    const auto path = dir / "crash.netj";
    std::mt19937 random(777);
    Document reference; // the first `applied` actions, in memory
    std::uint64_t applied = 0;
    std::uint64_t recoveredBefore = 0;
    int tornTails = 0, unacknowledgedKept = 0;
    for (int round = 0; round < 20; ++round) {
        INFO("round " << round);
        const std::uint64_t start = std::filesystem::exists(path) ? entriesOf(path).size() : 0;
        REQUIRE(start == recoveredBefore);
        int fds[2];
        REQUIRE(::pipe(fds) == 0);
        const pid_t pid = ::fork();
        REQUIRE(pid >= 0);
        if (pid == 0) {
            ::close(fds[0]);
            runChild(path, start, fds[1]);
        }
        ::close(fds[1]);
        // Let the child acknowledge a random number of entries (0: it may still be opening the
        // journal), then kill it a random moment later: mid-write, mid-sync, between entries.
        std::uint64_t acknowledged = start, value = 0;
        const int wanted = std::uniform_int_distribution<int>(0, 12)(random);
        for (int i = 0; i < wanted && ::read(fds[0], &value, sizeof value) == sizeof value; ++i) acknowledged = value;
        std::this_thread::sleep_for(std::chrono::microseconds(std::uniform_int_distribution<int>(0, 4000)(random)));
        ::kill(pid, SIGKILL);
        while (::read(fds[0], &value, sizeof value) == sizeof value) acknowledged = value;
        ::close(fds[0]);
        int status = 0;
        REQUIRE(::waitpid(pid, &status, 0) == pid);
        REQUIRE(WIFSIGNALED(status));
        REQUIRE(WTERMSIG(status) == SIGKILL);

        if (!std::filesystem::exists(path)) { // killed before the journal was first written
            REQUIRE(acknowledged == 0);
            continue;
        }
        std::vector<std::string> warnings;
        const Document recovered = Document::open(path, &warnings);
        tornTails += !warnings.empty();
        const std::uint64_t entries = entriesOf(path).size();
        INFO("acknowledged " << acknowledged << ", recovered " << entries);
        CHECK(entries >= acknowledged);     // every acknowledged command
        CHECK(entries <= acknowledged + 1); // at most the one in flight, which was issued
        unacknowledgedKept += entries == acknowledged + 1;
        while (applied < entries) applyAction(reference, applied++);
        REQUIRE(recovered.hash() == reference.hash());
        recoveredBefore = entries;
    }
    CHECK(recoveredBefore >= 60); // the children did get work done (6 acknowledged per round on average)
    WARN("recovered " << recoveredBefore << " entries over 20 kills; " << tornTails << " torn tails, "
                      << unacknowledgedKept << " synced-but-unacknowledged entries kept");
}

TEST_CASE("a temporary file a killed writer left beside a file goes at its next write", "[crash]") {
    TempDir dir;
    const pid_t child = fork(); // a writer that is gone by the time of the next write
    if (child == 0)
        _exit(0);
    REQUIRE(child > 0);
    waitpid(child, nullptr, 0);
    const auto leftover = [&](const std::string& name, bool old = true) {
        const std::filesystem::path path = dir / name;
        writeBytes(path, "netsculpt-snapshot 2\n{\"cut off");
        if (old) // left an hour ago: younger ones may be another host's writer at work
            std::filesystem::last_write_time(
                path, std::filesystem::file_time_type::clock::now() - std::chrono::hours(1));
        return path;
    };
    const std::string dead = std::to_string(child);
    const auto deadJournal = leftover("j.netj.tmp-" + dead + "-3");
    const auto deadSnapshot = leftover("s.nets.tmp-" + dead); // as older writers named them
    const std::vector<std::filesystem::path> kept = {
        leftover("other.netj.tmp-" + dead + "-3"),       // beside another file
        leftover("j.netj.tmp-" + std::to_string(getppid()) + "-3"), // a writer that still runs
        leftover("j.netj.tmp-" + dead + "-4", false),    // too young to be sure
        leftover("j.netj.tmp-2024-05-13"),               // a user's file named like one
        leftover("j.netj.tmp-" + dead + "-3.bak"),
        leftover("j.netj.tmp-99999999-1"),               // no process has such a pid
    };
    Document doc = fixtureDocument();
    doc.save(dir / "j.netj");
    doc.saveSnapshot(dir / "s.nets");
    CHECK_FALSE(std::filesystem::exists(deadJournal));
    CHECK_FALSE(std::filesystem::exists(deadSnapshot));
    for (const auto& path : kept) {
        INFO(path.filename());
        CHECK(std::filesystem::exists(path));
    }
    CHECK(Document::open(dir / "j.netj").hash() == doc.hash());
}
