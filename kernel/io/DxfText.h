#pragma once
// The bytes of a DXF file as UTF-8 text with LF line ends, before DxfScan and dxflib read them.

#include <string>

namespace netsculpt::io {

/// `bytes` of the DXF file `file` (its name for messages) made ready to read:
/// - a UTF-8 byte-order mark at the start is dropped;
/// - old Mac line ends (CR alone, no LF anywhere) become LF;
/// - text that is not UTF-8 in a drawing older than AutoCAD 2007 ($ACADVER before AC1021) is
///   decoded from its code page ($DWGCODEPAGE ANSI_1252, or ISO8859-1; none given: ANSI_1252).
///   Text that is valid UTF-8 stays as it is, whatever the header says (LibreCAD and QCAD write
///   UTF-8 under ANSI_1252). UserError naming the line, the byte and the code page for another
///   code page, and for bytes that are not UTF-8 in a drawing of 2007 or later.
/// Binary DXF and text with NUL bytes are returned unchanged (DxfScan refuses them).
std::string decodeDxfText(const std::string& file, std::string bytes);

} // namespace netsculpt::io
