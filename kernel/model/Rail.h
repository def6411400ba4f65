#pragma once
// A rail: a named curve that pieces hang from or connect to. The curve is immutable and shared
// between copies of the sculpture (undo snapshots copy rails for free).

#include "geometry/Curve.h"
#include "model/Ids.h"

#include <memory>
#include <string>

namespace netsculpt {

struct Rail {
    RailId id;
    std::string name;
    std::shared_ptr<const Curve> shape;
    const Curve& curve() const { return *shape; }
};

} // namespace netsculpt
