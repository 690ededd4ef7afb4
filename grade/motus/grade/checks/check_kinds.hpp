#pragma once
// The check kinds make_check (check.cpp) builds a test's check from, one a file beside this one
// (trajectory_check.cpp, ...): each reads its test's fields, as the class's constructor did there.
// Internal to the grade library.
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "motus/grade/check.hpp"
#include "motus/scene_file/json_fields.hpp"

namespace motus::grade::detail {

// Tests of the student's integrator, on a scene.
std::unique_ptr<Check> make_trajectory_check(JsonFields& f, const nlohmann::json& test, const SceneSource& source,
                                             const StudentParts& parts, const std::string& hint);
std::unique_ptr<Check> make_order_check(JsonFields& f, const nlohmann::json& test, const SceneSource& source,
                                        const StudentParts& parts, const std::string& hint);
std::unique_ptr<Check> make_stability_check(JsonFields& f, const nlohmann::json& test, const SceneSource& source,
                                            const StudentParts& parts, const std::string& hint);
std::unique_ptr<Check> make_energy_check(JsonFields& f, const nlohmann::json& test, const SceneSource& source,
                                         const StudentParts& parts, const std::string& hint);
// (No hint: its failures say what each failed condition usually means.)
std::unique_ptr<Check> make_adaptive_check(JsonFields& f, const nlohmann::json& test, const SceneSource& source,
                                           const StudentParts& parts);
// One step of the student's integrator, called directly.
std::unique_ptr<Check> make_step_check(JsonFields& f, const nlohmann::json& test, const StudentParts& parts,
                                       const std::string& hint);

// Tests of the student's collision rules and constraint projection.
std::unique_ptr<Check> make_scene_check(JsonFields& f, const nlohmann::json& test, const SceneSource& source,
                                        const StudentParts& parts, const std::string& hint);
std::unique_ptr<Check> make_call_check(JsonFields& f, const nlohmann::json& test, const StudentParts& parts,
                                       const std::string& hint);
std::unique_ptr<Check> make_project_check(JsonFields& f, const nlohmann::json& test, const StudentParts& parts,
                                          const std::string& hint);

}  // namespace motus::grade::detail
