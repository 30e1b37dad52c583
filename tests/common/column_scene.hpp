#pragma once
// The smallest valid scene the loader tests start from: a column of linear-elastic sand on a
// floor (tests append their own tables to it).

#include <string>

namespace duet::test {

inline const std::string kColumnScene = R"(name = "column"
spacing = 0.01
gravity = [0.0, -9.81]

[time]
end_time = 0.5

[material.sand]
model = "linear-elastic"
density = 1800.0
E = 1.0e6
nu = 0.3

[body.column]
material = "sand"
min = [0.0, 0.0]
max = [0.2, 0.1]

[wall.floor]
points = [[0.0, 0.0], [0.6, 0.0]]
)";

}  // namespace duet::test
