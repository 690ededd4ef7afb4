# The installed package works for a project of its own: install this build into an empty
# prefix, configure and build examples/ against that prefix only, run the example and find
# the course's spring table in what it prints (x = 20, 20, 10, −10, −35, −55 at t = 0 … 5,
# explicit Euler with m = 10, k = 5, h = 1: tests/reference/README.md).
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -P install_test.cmake
foreach(var BUILD_DIR SOURCE_DIR WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "install_test.cmake needs -D${var}=...")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${what} failed (${status}):\n${out}\n${err}")
  endif()
  set(output "${out}" PARENT_SCOPE)
endfunction()

run("cmake --install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(file bin/motus share/motus/scenes/spring.json share/motus/scene/scene.schema.json
             include/motus/simulation.hpp include/motus/scene_file/scene_file.hpp
             include/motus/compare/comparison.hpp include/motus/render/draw.hpp)
  if(NOT EXISTS ${prefix}/${file})
    message(FATAL_ERROR "the install has no ${file}")
  endif()
endforeach()
file(GLOB config ${prefix}/lib*/cmake/motus/motusConfig.cmake ${prefix}/lib/*/cmake/motus/motusConfig.cmake)
file(GLOB version ${prefix}/lib*/cmake/motus/motusConfigVersion.cmake ${prefix}/lib/*/cmake/motus/motusConfigVersion.cmake)
if(NOT config OR NOT version)
  message(FATAL_ERROR "the install has no motusConfig.cmake / motusConfigVersion.cmake")
endif()

# The example sees only the prefix: not this build tree, not the source tree's headers.
run("configuring examples/" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples -B ${WORK_DIR}/examples
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
run("building examples/" ${CMAKE_COMMAND} --build ${WORK_DIR}/examples)
run("spring_table" ${WORK_DIR}/examples/spring_table)
message(STATUS "spring_table printed:\n${output}")

# Rows "t x v a"; the course's table.
set(expected_x 20 20 10 -10 -35 -55)
set(expected_v 0 -10 -20 -25 -20 -2.5)
string(REPLACE "\n" ";" lines "${output}")
set(t 0)
foreach(line IN LISTS lines)
  string(STRIP "${line}" line)
  if(line MATCHES "^([-0-9.e+]+) +([-0-9.e+]+) +([-0-9.e+]+) +([-0-9.e+]+)$")
    list(GET expected_x ${t} x)
    list(GET expected_v ${t} v)
    if(NOT CMAKE_MATCH_1 STREQUAL "${t}" OR NOT CMAKE_MATCH_2 STREQUAL "${x}" OR NOT CMAKE_MATCH_3 STREQUAL "${v}")
      message(FATAL_ERROR "row ${t}: expected t = ${t}, x = ${x}, v = ${v}; got \"${line}\"")
    endif()
    math(EXPR t "${t} + 1")
  endif()
endforeach()
if(NOT t EQUAL 6)
  message(FATAL_ERROR "expected the 6 rows t = 0 … 5, found ${t}")
endif()

# head_on (masses 1 and 3 at +1 and −1 m/s, e = 1) ends at the exact v = (−2, 0) in every
# engine: motus to 1e-9, the peers to their float/double precision (README: all three exact).
file(GLOB scenes_dir LIST_DIRECTORIES true ${prefix}/share/motus/scenes)
run("head_on_in_three_engines" ${WORK_DIR}/examples/head_on_in_three_engines ${scenes_dir})
message(STATUS "head_on_in_three_engines printed:\n${output}")
foreach(engine motus box2d bullet)
  if(NOT output MATCHES "${engine} +(-?[0-9.]+) +(-?[0-9.]+)")
    message(FATAL_ERROR "no velocities for ${engine} in:\n${output}")
  endif()
  if(NOT CMAKE_MATCH_1 STREQUAL "-2.000000" OR NOT CMAKE_MATCH_2 MATCHES "^-?0.00000[0-9]$")
    message(FATAL_ERROR "${engine}: expected v = (-2, 0), got (${CMAKE_MATCH_1}, ${CMAKE_MATCH_2})")
  endif()
endforeach()

# The installed motus finds its installed scenes, not this build's ...
run("installed motus run spring" ${prefix}/bin/motus run spring --json)
if(NOT output MATCHES "share/motus/scenes/spring.json")
  message(FATAL_ERROR "the installed motus did not use the installed scenes:\n${output}")
endif()

# ... and its peers module (lib/motus/motus-peers.so): Box2D and Bullet run in its compare.
file(GLOB peers_module ${prefix}/lib*/motus/motus-peers.so ${prefix}/lib/*/motus/motus-peers.so)
if(NOT peers_module)
  message(FATAL_ERROR "the install has no lib/motus/motus-peers.so")
endif()
run("installed motus compare head_on" ${CMAKE_COMMAND} -E env --unset=MOTUS_PEERS_MODULE
    ${prefix}/bin/motus compare head_on --repeats 1 --json --out ${WORK_DIR}/compare)
foreach(engine box2d bullet)
  if(NOT output MATCHES "\"engine\": \"${engine}\"" OR output MATCHES "not supported by ${engine}")
    message(FATAL_ERROR "the installed motus did not run ${engine}:\n${output}")
  endif()
endforeach()

# ... and its expressions module (lib/motus/motus-expressions.so): a scene with an equations
# system runs (muparser is loaded from it).
file(GLOB expressions_module ${prefix}/lib*/motus/motus-expressions.so ${prefix}/lib/*/motus/motus-expressions.so)
if(NOT expressions_module)
  message(FATAL_ERROR "the install has no lib/motus/motus-expressions.so")
endif()
run("installed motus run lorenz_equations" ${CMAKE_COMMAND} -E env --unset=MOTUS_EXPRESSIONS_MODULE
    ${prefix}/bin/motus run lorenz_equations --steps 10 --json)
if(NOT output MATCHES "\"steps\": 10")
  message(FATAL_ERROR "the installed motus did not run lorenz_equations:\n${output}")
endif()

# Components: an optional one that does not exist (or whose Debian packages are missing) only
# leaves motus_<name>_FOUND false; a required one fails find_package with a message naming it.
file(MAKE_DIRECTORY ${WORK_DIR}/components)
file(WRITE ${WORK_DIR}/components/CMakeLists.txt [=[
cmake_minimum_required(VERSION 3.25)
project(components LANGUAGES CXX)
find_package(motus 0.1 REQUIRED COMPONENTS engine OPTIONAL_COMPONENTS nonesuch)
if(NOT TARGET motus::engine OR motus_nonesuch_FOUND OR NOT motus_engine_FOUND)
  message(FATAL_ERROR "optional: engine ${motus_engine_FOUND}, nonesuch ${motus_nonesuch_FOUND}")
endif()
find_package(motus 0.1 QUIET COMPONENTS nonesuch)
if(motus_FOUND OR NOT motus_NOT_FOUND_MESSAGE MATCHES "unknown component \"nonesuch\"")
  message(FATAL_ERROR "required unknown component: found ${motus_FOUND}, message ${motus_NOT_FOUND_MESSAGE}")
endif()
message(STATUS "components: as documented")
]=])
run("configuring a project with optional components" ${CMAKE_COMMAND} -S ${WORK_DIR}/components
    -B ${WORK_DIR}/components/build -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
if(NOT output MATCHES "components: as documented")
  message(FATAL_ERROR "the components project said:\n${output}")
endif()

# ... and its assignments (share/motus/assignments), without their solutions and hidden tests, and
# every relative link in their handouts leads to an installed file (../docs/grading.md led nowhere):
file(GLOB_RECURSE handouts ${prefix}/share/motus/assignments/*.md)
foreach(handout IN LISTS handouts)
  file(READ ${handout} text)
  # (A link's "](" marked first: a list element with a square bracket in it is not split at its
  # semicolons, and the matches came back as one.)
  string(REPLACE "](" "@LINK@" text "${text}")
  string(REGEX MATCHALL "@LINK@[^)#:]+[)#]" links "${text}")
  get_filename_component(folder ${handout} DIRECTORY)
  foreach(link IN LISTS links)
    string(REGEX REPLACE "^@LINK@([^)#]+)[)#]$" "\\1" target "${link}")
    if(NOT EXISTS ${folder}/${target})
      message(FATAL_ERROR "${handout} links to ${target}, which the install does not have")
    endif()
  endforeach()
endforeach()
# The installed motus grades the installed starter against its public tests.
foreach(assignment integrators collisions cloth)
  if(NOT EXISTS ${prefix}/share/motus/assignments/${assignment}/assignment.json
     OR EXISTS ${prefix}/share/motus/assignments/${assignment}/solution
     OR EXISTS ${prefix}/share/motus/assignments/${assignment}/hidden)
    message(FATAL_ERROR "the install's ${assignment} is not as documented (share/motus/assignments, no solution/ or hidden/)")
  endif()
endforeach()
run("installed motus grade integrators (its starter)" ${CMAKE_COMMAND} -E env --unset=MOTUS_ASSIGNMENTS
    ${prefix}/bin/motus grade integrators ${prefix}/share/motus/assignments/integrators/starter --no-sandbox
    --format gradescope)
if(NOT output MATCHES "\"max_score\"")
  message(FATAL_ERROR "the installed motus did not grade the installed starter:\n${output}")
endif()
# The starter passes exactly its assignment.json's starter_passes (the files, the build) and scores 0.
file(READ ${prefix}/share/motus/assignments/integrators/assignment.json assignment)
string(JSON expected_count LENGTH "${assignment}" starter_passes)
set(expected "")
math(EXPR last "${expected_count} - 1")
foreach(i RANGE ${last})
  string(JSON name GET "${assignment}" starter_passes ${i})
  list(APPEND expected ${name})
endforeach()
string(JSON score GET "${output}" score)
string(JSON test_count LENGTH "${output}" tests)
set(passed_tests "")
math(EXPR last "${test_count} - 1")
foreach(i RANGE ${last})
  string(JSON status GET "${output}" tests ${i} status)
  string(JSON name GET "${output}" tests ${i} name)
  string(REGEX REPLACE ":.*" "" name "${name}")  # ("build: The submission compiles…": the test's id)
  if(status MATCHES "^passed$")
    list(APPEND passed_tests ${name})
  endif()
endforeach()
if(NOT score MATCHES "^0(\\.0*)?$" OR NOT passed_tests STREQUAL expected)
  message(FATAL_ERROR "the installed starter scored ${score} and passed '${passed_tests}' (its assignment.json: 0 and "
                      "'${expected}'):\n${output}")
endif()
