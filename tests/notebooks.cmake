# The notebook notebooks/iterative_shadows.ipynb, executed headless against the CLI built here
# (label medium): nbconvert exits non-zero when any cell raises, and the notebook's cells assert
# what they rely on (class moments, moments adding up, clt == iterate for deterministic members).
# Kernel "python3" resolves to /usr/bin/python3 through notebooks/kernels (JUPYTER_PATH comes
# first in Jupyter's search path). Jupyter's and IPython's per-user directories are in the build
# tree: nothing is read from or written to HOME (jupyter created ~/.jupyter, and failed where HOME
# is not writable, e.g. HOME=/nonexistent). A second test checks that the checked-in notebook is exactly
# what scripts/make_notebook.py generates (outputs cleared).
find_program(ICS_PYTHON3_NB NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(ICS_PYTHON3_NB)
  execute_process(COMMAND ${ICS_PYTHON3_NB} -c "import nbformat, nbconvert, ipykernel, numpy, matplotlib"
    RESULT_VARIABLE ics_nb_rc OUTPUT_QUIET ERROR_QUIET)
endif()
set(ics_nb_dir ${CMAKE_CURRENT_BINARY_DIR}/notebooks)
# nbconvert globs its input: the notebook's path with '[', '*', '?' escaped as Python's
# glob.escape does (under /tmp/a[1]/main the pattern "matched no files")
string(REPLACE "[" "[[]" ics_nb_input "${CMAKE_SOURCE_DIR}/notebooks/iterative_shadows.ipynb")
string(REPLACE "*" "[*]" ics_nb_input "${ics_nb_input}")
string(REPLACE "?" "[?]" ics_nb_input "${ics_nb_input}")
# section 7 imports the Python package (the fixture python_install builds it): required where
# the interpreter has cffi, as make test's machine does; elsewhere the section explains itself
set(ics_nb_require_package "")
if(ICS_PYTHON3_NB AND NOT ICS_SANITIZE)
  execute_process(COMMAND ${ICS_PYTHON3_NB} -c "import cffi, setuptools, pip"
    RESULT_VARIABLE ics_nb_cffi_rc OUTPUT_QUIET ERROR_QUIET)
  if(ics_nb_cffi_rc EQUAL 0)
    set(ics_nb_require_package 1)
  endif()
endif()
if(ICS_PYTHON3_NB AND ics_nb_rc EQUAL 0)
  add_test(NAME notebook_iterative_shadows COMMAND ${CMAKE_COMMAND} -E env
    JUPYTER_PATH=${CMAKE_SOURCE_DIR}/notebooks
    JUPYTER_RUNTIME_DIR=${ics_nb_dir}/runtime
    JUPYTER_CONFIG_DIR=${ics_nb_dir}/config
    JUPYTER_DATA_DIR=${ics_nb_dir}/data
    IPYTHONDIR=${ics_nb_dir}/ipython
    MPLCONFIGDIR=${ics_nb_dir}/mpl
    PYDEVD_DISABLE_FILE_VALIDATION=1
    ICSHADOW_CLI=$<TARGET_FILE:icshadow_cli>
    ${ICS_PYTHON_ENV} ICSHADOW_REQUIRE_PACKAGE=${ics_nb_require_package}
    ${ICS_PYTHON3_NB} -m nbconvert --to notebook --execute
      --ExecutePreprocessor.kernel_name=python3 --ExecutePreprocessor.timeout=600
      --output-dir ${ics_nb_dir} ${ics_nb_input})
  set_tests_properties(notebook_iterative_shadows PROPERTIES LABELS medium TIMEOUT 900
    FIXTURES_REQUIRED icshadow_python)
  # paths go in as arguments, never into the script text (a checkout path with blanks)
  add_test(NAME notebook_generated COMMAND sh -c
    "mkdir -p \"$1\" && \"$2\" \"$3\" \"$1/generated.ipynb\" && cmp \"$1/generated.ipynb\" \"$4\""
    notebook_generated ${ics_nb_dir} ${ICS_PYTHON3_NB} ${CMAKE_SOURCE_DIR}/scripts/make_notebook.py
    ${CMAKE_SOURCE_DIR}/notebooks/iterative_shadows.ipynb)
  set_tests_properties(notebook_generated PROPERTIES LABELS fast)
else()
  foreach(t notebook_iterative_shadows notebook_generated)
    add_test(NAME ${t} COMMAND ${CMAKE_COMMAND} -E echo
      "SKIPPED: ${t} needs /usr/bin/python3 with nbformat, nbconvert, ipykernel, numpy, matplotlib (scripts/deps.sh)")
    set_tests_properties(${t} PROPERTIES LABELS medium SKIP_REGULAR_EXPRESSION "SKIPPED:")
  endforeach()
endif()
