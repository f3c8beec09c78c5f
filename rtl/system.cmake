# Verilated builds of a system of units (rtl/tess_system.sv; the cycle model is sim::UnitSystem),
# included by rtl/CMakeLists.txt with TESSIM_BUILD_SYSTEM_RTL. The models go into
# tessim_rtl_models beside the unit's (one Verilator runtime), outside the unit's variant table
# (make_rtl_unit does not know them): tests/system_rtl/ drives them directly.
#
# Units of the smallest unit build, n1 (IntBlocks = 1, the other tess_unit parameters at their
# defaults). The m2 and m4 builds take the policy, the dispatch batch and the slots in use (2..64)
# from cfg_*_i (RuntimeConfig = 1) and have P = M ports (a test runs P < M by never readying the
# ports above P); m2_fixed has them as parameters (RuntimeConfig = 0: the parameter path), P = 1,
# R = 4, earliest_finish, batch 3, and random X values at power-up. All check assertions.
tessim_rtl_list(TESSIM_SYSTEM_RTL_SOURCES ${TESSIM_RTL_DIR}/system.f)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${TESSIM_SYSTEM_RTL_SOURCES})

# tessim_verilate_system(<prefix> <verilator args>...)
function(tessim_verilate_system prefix)
  get_property(model_dir GLOBAL PROPERTY TESSIM_RTL_MODEL_DIR)
  set(args_file ${model_dir}/${prefix}.dir/verilator_args.txt)
  foreach(src ${TESSIM_RTL_SOURCES} ${TESSIM_SYSTEM_RTL_SOURCES})
    if(EXISTS ${args_file} AND ${src} IS_NEWER_THAN ${args_file})
      file(REMOVE ${args_file})
    endif()
  endforeach()
  verilate(tessim_rtl_models
    PREFIX ${prefix}
    TOP_MODULE tess_system
    SOURCES ${TESSIM_RTL_SOURCES} ${TESSIM_SYSTEM_RTL_SOURCES}
    VERILATOR_ARGS -O3 --assert ${ARGN}
    OPT_FAST -O3
    OPT_SLOW -O1
    OPT_GLOBAL -O2)
endfunction()

set(system_unit -GIntBlocks=1)
tessim_verilate_system(Vtess_system_m2 --x-assign fast --x-initial fast ${system_unit}
                       -GUnits=2 -GGePorts=2 -GReorderSlots=64 -GRuntimeConfig=1)
tessim_verilate_system(Vtess_system_m4 --x-assign fast --x-initial fast ${system_unit}
                       -GUnits=4 -GGePorts=4 -GReorderSlots=64 -GRuntimeConfig=1)
tessim_verilate_system(Vtess_system_m2_fixed --x-assign unique --x-initial unique ${system_unit}
                       -GUnits=2 -GGePorts=1 -GReorderSlots=4 -GDistribution=2 -GDispatchBatch=3
                       -GRuntimeConfig=0)

# Lint (every warning of -Wall) and the Yosys read of the system, with the parameters away from
# their defaults.
if(TESSIM_BUILD_TESTS)
  enable_testing()
  add_test(NAME system_rtl_lint
           COMMAND verilator --lint-only -Wall ${TESSIM_RTL_SOURCES} ${TESSIM_SYSTEM_RTL_SOURCES} --top tess_system
                   -GUnits=3 -GGePorts=2 -GReorderSlots=5 -GDistribution=2 -GDispatchBatch=3)
  set_tests_properties(system_rtl_lint PROPERTIES FAIL_REGULAR_EXPRESSION "%Warning|%Error")
  find_program(TESSIM_YOSYS yosys)
  if(TESSIM_YOSYS)
    list(JOIN TESSIM_RTL_SOURCES " " system_yosys_unit)
    list(JOIN TESSIM_SYSTEM_RTL_SOURCES " " system_yosys_sources)
    add_test(NAME system_rtl_yosys_read
             COMMAND ${TESSIM_YOSYS} -q -p "read_verilog -sv ${system_yosys_unit} ${system_yosys_sources}; hierarchy -check -top tess_system")
    set_tests_properties(system_rtl_yosys_read PROPERTIES FAIL_REGULAR_EXPRESSION "Warning|ERROR")
  endif()
endif()
