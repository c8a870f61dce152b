# mocaplink_fuzz(NAME SOURCE LIBS...)
# Every parser of outside bytes has one fuzz target: fuzz/NAME.cpp defines LLVMFuzzerTestOneInput.
# Always built: NAME_replay, which runs every file of fuzz/corpus/NAME once (CTest label fuzz-replay).
# With MOCAPLINK_FUZZ=ON and clang: NAME, a libFuzzer binary with ASan+UBSan.
function(mocaplink_fuzz name source)
  add_executable(${name}_replay ${source} ${PROJECT_SOURCE_DIR}/fuzz/replay_main.cpp)
  target_link_libraries(${name}_replay PRIVATE ${ARGN})
  mocaplink_warnings(${name}_replay)
  mocaplink_test_flags(${name}_replay)
  add_test(NAME fuzz_replay.${name}
           COMMAND ${name}_replay ${PROJECT_SOURCE_DIR}/fuzz/corpus/${name})
  set_tests_properties(fuzz_replay.${name} PROPERTIES LABELS fuzz-replay)
  if(MOCAPLINK_FUZZ)
    add_executable(${name} ${source})
    target_link_libraries(${name} PRIVATE ${ARGN})
    target_compile_options(${name} PRIVATE -fsanitize=fuzzer,address,undefined -g)
    target_link_options(${name} PRIVATE -fsanitize=fuzzer,address,undefined)
  endif()
endfunction()
