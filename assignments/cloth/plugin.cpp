// The cloth assignment as a motus plug-in: your satisfy_constraints (cloth.cpp) takes the place
// of motus's own constraint projection in every Verlet run that loads it. This file is the
// assignment's; the grader uses its own copy, so there is nothing to change here.
#include "cloth.hpp"
#include "motus/student/plugin.hpp"

MOTUS_PLUGIN("student", "the cloth assignment (cloth.cpp)") { plugin.constraints(student::satisfy_constraints); }
