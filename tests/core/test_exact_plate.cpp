#define BOOST_TEST_MODULE exact_plate
#include <boost/test/unit_test.hpp>
#include "modalbench/exact.hpp"
BOOST_AUTO_TEST_CASE(placeholder_plate) { BOOST_TEST(true); }
