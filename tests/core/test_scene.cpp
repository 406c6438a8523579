#define BOOST_TEST_MODULE scene
#include <boost/test/unit_test.hpp>
#include "modalbench/scene.hpp"
BOOST_AUTO_TEST_CASE(placeholder_scene) { BOOST_TEST(true); }
