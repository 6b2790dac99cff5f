# intgrid_write_if_changed(PATH TEXT): writes TEXT to PATH only when PATH does not hold it
# already, so that what is built from PATH is not rebuilt at every configure. Usable in a
# project and in a `cmake -P` script alike. (file(CONFIGURE) would also keep the file, but it
# expands @VAR@, which SystemVerilog's `@(posedge clk)` is not.)
function(intgrid_write_if_changed path text)
  set(old "")
  if(EXISTS ${path})
    file(READ ${path} old)
  endif()
  if(NOT old STREQUAL text)
    file(WRITE ${path} "${text}")
  endif()
endfunction()
