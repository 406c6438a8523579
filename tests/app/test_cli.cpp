#define BOOST_TEST_MODULE cli
#include <boost/test/unit_test.hpp>
BOOST_AUTO_TEST_CASE(placeholder_cli) { BOOST_TEST(true); }
