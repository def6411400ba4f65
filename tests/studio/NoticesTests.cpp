// The status line after an export: plain for a relaxed shape, a warning naming the stiffness and
// the factor for a soft preview's shape, and for a shape not relaxed at all; after an open or a
// restore: the warnings of reading the journal with it.

#include "Notices.h"

#include <catch2/catch.hpp>

using namespace netsculpt::studio;

TEST_CASE("export notice: a relaxed shape is exported without a warning", "[studio]") {
    const Notice notice = exportNotice("out/knots.csv", true, 1.0);
    CHECK(notice.text == "exported out/knots.csv");
    CHECK_FALSE(notice.error);
}

TEST_CASE("export notice: a preview's shape warns with its stiffness and how far off its forces "
          "read",
          "[studio]") {
    const Notice notice = exportNotice("report.json", false, 0.01);
    CHECK(notice.error);
    CHECK_THAT(notice.text, Catch::Matchers::StartsWith("exported report.json: not the relaxed") &&
                                Catch::Matchers::Contains("x0.01 stiffness") &&
                                Catch::Matchers::Contains("about 100 times too large") &&
                                Catch::Matchers::Contains("Refine, then export again"));
    // The continuation's softest stage.
    CHECK_THAT(exportNotice("a.glb", false, 0.00025).text,
               Catch::Matchers::Contains("x0.00025 stiffness") &&
                   Catch::Matchers::Contains("about 4000 times"));
}

TEST_CASE("export notice: a shape not relaxed at all (the initial geometry, a refine under way) "
          "warns that its forces are not final",
          "[studio]") {
    const Notice notice = exportNotice("a.obj", false, 1.0);
    CHECK(notice.error);
    CHECK_THAT(notice.text, Catch::Matchers::Contains("not the relaxed shape") &&
                                Catch::Matchers::Contains("are not final"));
    CHECK_THAT(notice.text, !Catch::Matchers::Contains("times too large"));
}

TEST_CASE("open notice: a torn last entry dropped is shown with the outcome, in the error colour",
          "[studio]") {
    const std::string torn = "s.netj line 9: dropped a torn last entry (no end of line, so it "
                             "was never acknowledged)";
    const Notice restored = openNotice("restored the last session (s.netj)", {torn});
    CHECK(restored.error);
    CHECK(restored.text == "restored the last session (s.netj), but " + torn);
    const Notice two = openNotice("opened d.netj", {"first", "second"});
    CHECK(two.text == "opened d.netj, but first; second");
    const Notice clean = openNotice("opened d.netj", {});
    CHECK_FALSE(clean.error);
    CHECK(clean.text == "opened d.netj");
}
