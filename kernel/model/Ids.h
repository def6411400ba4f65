#pragma once
// Stable ids that name rails and pieces across the kernel, the Lua binding and the journal.
// An id is a small number passed by value; 0 is the null id. Ids are never reused within a
// sculpture, so an id that was removed stays recognisably dead ("piece 7 was removed").

#include <compare>
#include <cstdint>
#include <functional>
#include <string>

namespace netsculpt {

template <typename Tag> struct Id {
    std::uint32_t value = 0; ///< 0 = null
    constexpr Id() = default;
    constexpr explicit Id(std::uint32_t v) : value(v) {}
    constexpr explicit operator bool() const { return value != 0; }
    constexpr auto operator<=>(const Id&) const = default;
};

struct RailTag {};
struct PieceTag {};
using RailId = Id<RailTag>;   ///< prints as "rail N"
using PieceId = Id<PieceTag>; ///< prints as "piece N"

inline std::string toString(RailId id) { return "rail " + std::to_string(id.value); }
inline std::string toString(PieceId id) { return "piece " + std::to_string(id.value); }

} // namespace netsculpt

template <typename Tag> struct std::hash<netsculpt::Id<Tag>> {
    std::size_t operator()(netsculpt::Id<Tag> id) const noexcept { return id.value; }
};
