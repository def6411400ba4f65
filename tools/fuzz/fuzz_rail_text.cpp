// importRailsFile on an .obj or a .csv. The first byte picks the reader and the options (bit 0:
// CSV, else OBJ; bit 1: units = "ft"); the rest is the file.

#include "FuzzSupport.h"

#include "io/Import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace netsculpt;
    if (size < 1)
        return 0;
    ImportOptions options;
    if (data[0] & 2)
        options.units = "ft";
    const auto file = fuzz::writeInput((data[0] & 1) ? "rails.csv" : "rails.obj",
                                       fuzz::bytesOf(data + 1, size - 1));
    fuzz::refusesOnlyWithUserErrors("importRailsFile (OBJ, CSV)",
                                    [&] { (void)importRailsFile(file, options); });
    return 0;
}
