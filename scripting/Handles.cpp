#include "scripting/Handles.h"

#include "scripting/Wrap.h"

#include <cstring>
#include <new>

namespace netsculpt::lua {

namespace {

constexpr int kRailCache = 1;
constexpr int kPieceCache = 2;

struct DocumentBox {
    Document doc;
    bool alive = true;
};

struct HandleBox {
    std::uint32_t id = 0;
    std::uint64_t birth = 0; ///< Document::birth of the id when the handle was made
};

DocumentBox* toDocument(lua_State* L, int index) {
    return static_cast<DocumentBox*>(luaL_testudata(L, index, kDocumentType));
}

/// The kind a handle metatable name stands for, for messages.
const char* kindOf(const char* type) {
    return type == kPieceType ? "piece" : "rail";
}

int documentGc(lua_State* L) {
    auto* box = static_cast<DocumentBox*>(lua_touserdata(L, 1));
    if (box != nullptr && box->alive) {
        box->alive = false;
        box->doc.~Document();
    }
    return 0;
}

int documentToString(lua_State* L) {
    const DocumentBox* box = toDocument(L, 1);
    if (box == nullptr || !box->alive) {
        lua_pushliteral(L, "netsculpt sculpture (closed)");
        return 1;
    }
    const Sculpture& s = box->doc.sculpture();
    const int rails = int(s.rails.size()), pieces = int(s.pieces.size());
    lua_pushfstring(L, "netsculpt sculpture (%d rail%s, %d piece%s)", rails, rails == 1 ? "" : "s",
                    pieces, pieces == 1 ? "" : "s");
    return 1;
}

int handleToString(lua_State* L) {
    lua_pushstring(L, describeHandle(L, 1).c_str());
    return 1;
}

/// Handles compare equal by id; within a document also by birth (a piece made again with the id
/// of an undone one is another piece).
int handleEq(lua_State* L) {
    const std::string a = describeHandle(L, 1), b = describeHandle(L, 2);
    bool same = !a.empty() && a == b;
    if (same) {
        const auto* x = static_cast<const HandleBox*>(lua_touserdata(L, 1));
        const auto* y = static_cast<const HandleBox*>(lua_touserdata(L, 2));
        lua_getiuservalue(L, 1, 1);
        lua_getiuservalue(L, 2, 1);
        same = x->birth == y->birth || lua_rawequal(L, -1, -2) == 0;
        lua_pop(L, 2);
    }
    lua_pushboolean(L, same);
    return 1;
}

/// __index of handles: h.id, else the methods table (upvalue 1).
int handleIndex(lua_State* L) {
    if (lua_type(L, 2) == LUA_TSTRING && std::strcmp(lua_tostring(L, 2), "id") == 0) {
        lua_pushinteger(L, static_cast<HandleBox*>(lua_touserdata(L, 1))->id);
        return 1;
    }
    lua_pushvalue(L, 2);
    lua_rawget(L, lua_upvalueindex(1));
    return 1;
}

void newHandleType(lua_State* L, const char* type, void (*addMethods)(lua_State*)) {
    luaL_newmetatable(L, type);
    lua_newtable(L);
    addMethods(L);
    lua_pushcclosure(L, handleIndex, 1);
    lua_setfield(L, -2, "__index");
    lua_pushcfunction(L, handleToString);
    lua_setfield(L, -2, "__tostring");
    lua_pushcfunction(L, handleEq);
    lua_setfield(L, -2, "__eq");
    lua_pushliteral(L, "locked");
    lua_setfield(L, -2, "__metatable");
    lua_pop(L, 1);
}

/// Document::birth of a piece or rail id.
std::uint64_t birthOf(lua_State* L, int docIndex, const char* type, std::uint32_t id) {
    const Document& doc = toDocument(L, docIndex)->doc;
    return type == kPieceType ? doc.birth(PieceId(id)) : doc.birth(RailId(id));
}

void pushHandle(lua_State* L, int docIndex, const char* type, int cache, std::uint32_t id) {
    docIndex = lua_absindex(L, docIndex);
    const std::uint64_t birth = birthOf(L, docIndex, type, id);
    lua_getiuservalue(L, docIndex, 1);
    lua_rawgeti(L, -1, cache);
    lua_remove(L, -2);
    if (lua_rawgeti(L, -1, id) == LUA_TUSERDATA &&
        static_cast<const HandleBox*>(lua_touserdata(L, -1))->birth == birth) {
        lua_remove(L, -2);
        return;
    }
    lua_pop(L, 1);
    auto* box = static_cast<HandleBox*>(lua_newuserdatauv(L, sizeof(HandleBox), 1));
    box->id = id;
    box->birth = birth;
    luaL_setmetatable(L, type);
    lua_pushvalue(L, docIndex);
    lua_setiuservalue(L, -2, 1);
    lua_pushvalue(L, -1);
    lua_rawseti(L, -3, id);
    lua_remove(L, -2);
}

/// The id of the handle at `index` after checking its type, its document and its liveness.
/// `arg` names the argument in messages; null for the handle of a method call (p:info()).
std::uint32_t checkHandle(const Call& call, int index, const char* arg, int docIndex,
                          const char* type) {
    lua_State* L = call.L;
    const auto* box = static_cast<const HandleBox*>(luaL_testudata(L, index, type));
    if (box == nullptr)
        call.bad(arg != nullptr ? arg : kindOf(type), index,
                 std::string("a ") + kindOf(type) + " handle");
    lua_getiuservalue(L, index, 1);
    const bool sameDocument = lua_rawequal(L, -1, docIndex) != 0;
    lua_pop(L, 1);
    if (!sameDocument)
        call.fail(std::string("argument '") + arg + "' is " + describeHandle(L, index) +
                  " of another sculpture");
    const Sculpture& s = toDocument(L, docIndex)->doc.sculpture();
    const bool piece = type == kPieceType;
    const bool present = piece ? s.hasPiece(PieceId(box->id)) : s.hasRail(RailId(box->id));
    const bool itself = box->birth == birthOf(L, docIndex, type, box->id);
    if (!present || !itself) {
        const std::uint32_t next = piece ? s.nextPieceId : s.nextRailId;
        const std::string what =
            arg == nullptr ? std::string() : std::string("argument '") + arg + "': ";
        const bool removed = box->id < next && itself;
        call.fail(what + describeHandle(L, index) +
                  (removed ? " was removed"
                           : " no longer exists (the call that made it was undone; its id now "
                             "names another " +
                                 std::string(kindOf(type)) + " or none)"));
    }
    return box->id;
}

std::uint32_t handleSelf(const Call& call, const char* type, int& docIndex) {
    lua_State* L = call.L;
    if (luaL_testudata(L, 1, type) == nullptr)
        call.fail(std::string("call it as ") + kindOf(type) + ":" + call.name +
                  "() (with a colon), got " + describe(L, 1) + " as the " + kindOf(type));
    lua_getiuservalue(L, 1, 1);
    docIndex = lua_gettop(L);
    if (!toDocument(L, docIndex)->alive)
        call.fail("the sculpture of this handle was closed");
    return checkHandle(call, 1, nullptr, docIndex, type);
}

} // namespace

Document& pushDocument(lua_State* L, Document&& doc) {
    void* memory = lua_newuserdatauv(L, sizeof(DocumentBox), 1);
    auto* box = new (memory) DocumentBox{std::move(doc)};
    luaL_setmetatable(L, kDocumentType);
    lua_createtable(L, 2, 0);
    for (int cache : {kRailCache, kPieceCache}) {
        lua_newtable(L);
        lua_createtable(L, 0, 1);
        lua_pushliteral(L, "v");
        lua_setfield(L, -2, "__mode");
        lua_setmetatable(L, -2);
        lua_rawseti(L, -2, cache);
    }
    lua_setiuservalue(L, -2, 1);
    return box->doc;
}

Document& checkDocument(const Call& call, int index) {
    DocumentBox* box = toDocument(call.L, index);
    if (box == nullptr)
        call.fail(std::string("call it as doc:") + call.name + "(...) (with a colon), got " +
                  describe(call.L, index) + " as the sculpture");
    if (!box->alive)
        call.fail("the sculpture was closed");
    return box->doc;
}

void pushPiece(lua_State* L, int docIndex, PieceId id) {
    pushHandle(L, docIndex, kPieceType, kPieceCache, id.value);
}
void pushRail(lua_State* L, int docIndex, RailId id) {
    pushHandle(L, docIndex, kRailType, kRailCache, id.value);
}

PieceId checkPiece(const Call& call, int index, const char* arg, int docIndex) {
    return PieceId(checkHandle(call, index, arg, docIndex, kPieceType));
}

RailId checkRail(const Call& call, int index, const char* arg, int docIndex) {
    return RailId(checkHandle(call, index, arg, docIndex, kRailType));
}

PieceId pieceArg(const TableArgs& args, const char* key, int docIndex) {
    const int at = args.push(key);
    if (lua_isnil(args.call().L, at))
        args.missing(key, "a piece handle");
    const PieceId id = checkPiece(args.call(), at, key, docIndex);
    args.pop();
    return id;
}

RailId railArg(const TableArgs& args, const char* key, int docIndex) {
    const int at = args.push(key);
    if (lua_isnil(args.call().L, at))
        args.missing(key, "a rail handle");
    const RailId id = checkRail(args.call(), at, key, docIndex);
    args.pop();
    return id;
}

int handleDocument(const Call& call, PieceId& id) {
    int docIndex = 0;
    id = PieceId(handleSelf(call, kPieceType, docIndex));
    return docIndex;
}

int handleDocument(const Call& call, RailId& id) {
    int docIndex = 0;
    id = RailId(handleSelf(call, kRailType, docIndex));
    return docIndex;
}

std::string describeHandle(lua_State* L, int index) {
    if (const auto* box = static_cast<const HandleBox*>(luaL_testudata(L, index, kPieceType)))
        return "piece " + std::to_string(box->id);
    if (const auto* box = static_cast<const HandleBox*>(luaL_testudata(L, index, kRailType)))
        return "rail " + std::to_string(box->id);
    if (luaL_testudata(L, index, kDocumentType) != nullptr)
        return "a sculpture";
    return "";
}

void registerHandleTypes(lua_State* L) {
    if (luaL_newmetatable(L, kDocumentType) == 0) {
        lua_pop(L, 1);
        return; // already registered in this state
    }
    lua_newtable(L);
    addDocumentMethods(L);
    lua_setfield(L, -2, "__index");
    lua_pushcfunction(L, documentGc);
    lua_setfield(L, -2, "__gc");
    lua_pushcfunction(L, documentToString);
    lua_setfield(L, -2, "__tostring");
    lua_pushliteral(L, "locked");
    lua_setfield(L, -2, "__metatable");
    lua_pop(L, 1);
    newHandleType(L, kPieceType, addPieceHandleMethods);
    newHandleType(L, kRailType, addRailHandleMethods);
}

} // namespace netsculpt::lua
