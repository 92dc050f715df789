# Fails when PROGRAM's dynamic section needs OpenImageIO (it must load it only through libskinspec_images.so).
execute_process(COMMAND readelf -d ${PROGRAM} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "readelf failed: ${err}")
endif()
if(out MATCHES "OpenImageIO")
  message(FATAL_ERROR "the program links OpenImageIO:\n${out}")
endif()
