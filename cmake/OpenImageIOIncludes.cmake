# Included after find_package(OpenImageIO) by the main build and the fuzz
# build. Debian's OpenImageIO config lists /usr/include/opencv4 even when OpenCV is
# not installed; OpenCV is not needed, so drop include paths that do not exist.
foreach(_oiio_target OpenImageIO::OpenImageIO OpenImageIO::OpenImageIO_Util)
  if(TARGET ${_oiio_target})
    get_target_property(_dirs ${_oiio_target} INTERFACE_INCLUDE_DIRECTORIES)
    if(_dirs)
      set(_kept)
      foreach(_d IN LISTS _dirs)
        if(EXISTS "${_d}")
          list(APPEND _kept "${_d}")
        endif()
      endforeach()
      set_target_properties(${_oiio_target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_kept}")
    endif()
  endif()
endforeach()
