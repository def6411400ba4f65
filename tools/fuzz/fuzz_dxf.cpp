// importRailsFile on a .dxf. The first byte picks the options (bit 0: units = "mm", so that
// unitless drawings get past the unit check); the rest is the file.

#include "FuzzSupport.h"

#include "io/Import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace netsculpt;
    if (size < 1)
        return 0;
    ImportOptions options;
    if (data[0] & 1)
        options.units = "mm";
    const auto file = fuzz::writeInput("rails.dxf", fuzz::bytesOf(data + 1, size - 1));
    fuzz::refusesOnlyWithUserErrors("importRailsFile (DXF)",
                                    [&] { (void)importRailsFile(file, options); });
    return 0;
}
