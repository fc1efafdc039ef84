#include <tressvk/asset.hpp>
