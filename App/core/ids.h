// Strong ids: a FaceId cannot be passed where an EdgeId is expected.
//
// Model entity ids (VertexId, EdgeId, FaceId) hold the 1-based TopExp::MapShapes index
// of the entity in its solid, so FaceId{7} is "Face7" in FreeCAD as well. Mesh ids
// (NodeId, HexId) are 0-based positions in a HexMesh.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

namespace vorohex::core {

template <class Tag>
class StrongId {
 public:
  constexpr StrongId() = default;
  constexpr explicit StrongId(std::int32_t value) : value_(value) {}
  constexpr std::int32_t value() const { return value_; }
  constexpr bool valid() const { return value_ >= 0; }
  friend constexpr bool operator==(StrongId a, StrongId b) { return a.value_ == b.value_; }
  friend constexpr bool operator!=(StrongId a, StrongId b) { return a.value_ != b.value_; }
  friend constexpr bool operator<(StrongId a, StrongId b) { return a.value_ < b.value_; }

 private:
  std::int32_t value_ = -1;
};

struct VertexTag {};
struct EdgeTag {};
struct FaceTag {};
struct SolidTag {};
struct NodeTag {};
struct HexTag {};

using VertexId = StrongId<VertexTag>;
using EdgeId = StrongId<EdgeTag>;
using FaceId = StrongId<FaceTag>;
using SolidId = StrongId<SolidTag>;
using NodeId = StrongId<NodeTag>;
using HexId = StrongId<HexTag>;

// FreeCAD's sub-element names: "Vertex3", "Edge5", "Face7".
inline std::string entity_name(VertexId id) {
  return "Vertex" + std::to_string(id.value());
}
inline std::string entity_name(EdgeId id) {
  return "Edge" + std::to_string(id.value());
}
inline std::string entity_name(FaceId id) {
  return "Face" + std::to_string(id.value());
}

}  // namespace vorohex::core

template <class Tag>
struct std::hash<vorohex::core::StrongId<Tag>> {
  std::size_t operator()(vorohex::core::StrongId<Tag> id) const noexcept {
    return std::hash<std::int32_t>()(id.value());
  }
};
