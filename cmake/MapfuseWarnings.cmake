# One place that sets the project's compiler warnings.
function(mapfuse_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wno-unused-parameter)
endfunction()
