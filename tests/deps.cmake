# scripts/deps.sh per job (`make demo` installs only the demo's packages): every job's packages
# among the full list that `make test` installs, the core in each, an unknown job refused
add_test(NAME deps_jobs COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/deps_jobs.sh ${CMAKE_SOURCE_DIR}/scripts/deps.sh)
set_tests_properties(deps_jobs PROPERTIES LABELS fast)
