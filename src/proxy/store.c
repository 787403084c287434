#include "proxy/store.h"

DFL_NAMES_DEFINE(dfl_proxy_storage, DFL_PROXY_STORAGE_LIST, DFL_PROXY_STORAGE_COUNT,
                 dfl_proxy_storage_names, dfl_proxy_storage_name, dfl_proxy_storage_parse,
                 "storage")
DFL_NAMES_DEFINE(dfl_proxy_position, DFL_PROXY_POSITION_LIST, DFL_PROXY_POSITION_COUNT,
                 dfl_proxy_position_names, dfl_proxy_position_name, dfl_proxy_position_parse,
                 "position")
