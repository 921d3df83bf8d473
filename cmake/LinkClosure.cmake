# acomms_link_closure(<target> <out-var>): every project or imported target
# that <target> links, directly or through the link interfaces of what it
# links, as seen at configure time.
#
# Used to check the layering where the compiler cannot: a static library on
# a link line pulls in only the objects something references, so a wrong
# link (acommsd on the evaluation library) can lie unused in the binary
# until the day it is used. The link interface shows it at once.
#
# Entries that are not targets (plain libraries, linker flags, directory
# markers) and generator expressions other than $<LINK_ONLY:...> are skipped.
function(acomms_link_closure target out)
  set(seen "")
  set(pending "${target}")
  while(pending)
    list(POP_FRONT pending item)
    string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" item "${item}")
    if(NOT TARGET "${item}")
      continue()
    endif()
    get_target_property(aliased "${item}" ALIASED_TARGET)
    if(aliased)
      set(item "${aliased}")
    endif()
    if(item IN_LIST seen)
      continue()
    endif()
    list(APPEND seen "${item}")
    foreach(property LINK_LIBRARIES INTERFACE_LINK_LIBRARIES)
      get_target_property(links "${item}" ${property})
      if(links)
        list(APPEND pending ${links})
      endif()
    endforeach()
  endwhile()
  list(REMOVE_ITEM seen "${target}")
  set(${out} "${seen}" PARENT_SCOPE)
endfunction()
