// NREL SPA (Reda & Andreas 2004/2008, NREL/TP-560-34302). Equation numbers refer to the report.
#include "demlight/geo/solar_position.h"

#include "demlight/core/error.h"

#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <span>

namespace demlight {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegPerRad = 180.0 / kPi;
constexpr double kJ2000 = 2451545.0;            // Julian Day of 2000-01-01 12:00 TT
constexpr double kDaysPerCentury = 36525.0;
constexpr double kSecondsPerDay = 86400.0;
constexpr double kEarthEquatorialRadiusM = 6378140.0;  // Eq. 38-39
constexpr double kEarthPolarRatio = 0.99664719;        // b/a of the earth ellipsoid, Eq. 36

double rad(double deg) { return deg / kDegPerRad; }
double deg(double r) { return r * kDegPerRad; }

/// Angle reduced to [0, 360).
double wrap360(double d) {
    d = std::fmod(d, 360.0);
    return d < 0 ? d + 360.0 : d;
}
/// Angle reduced to [-180, 180).
double wrap180(double d) { return wrap360(d + 180.0) - 180.0; }
/// Fraction reduced to [0, 1).
double wrapUnit(double x) { return x - std::floor(x); }

// --- Earth periodic terms (report Table A4.2): value = Σ A cos(B + C·JME), units 1e-8 rad/AU ---

struct PeriodicTerm {
    double a, b, c;
};

constexpr PeriodicTerm kL0[] = {
    {175347046, 0, 0},           {3341656, 4.6692568, 6283.07585}, {34894, 4.6261, 12566.1517},
    {3497, 2.7441, 5753.3849},   {3418, 2.8289, 3.5231},           {3136, 3.6277, 77713.7715},
    {2676, 4.4181, 7860.4194},   {2343, 6.1352, 3930.2097},        {1324, 0.7425, 11506.7698},
    {1273, 2.0371, 529.691},     {1199, 1.1096, 1577.3435},        {990, 5.233, 5884.927},
    {902, 2.045, 26.298},        {857, 3.508, 398.149},            {780, 1.179, 5223.694},
    {753, 2.533, 5507.553},      {505, 4.583, 18849.228},          {492, 4.205, 775.523},
    {357, 2.92, 0.067},          {317, 5.849, 11790.629},          {284, 1.899, 796.298},
    {271, 0.315, 10977.079},     {243, 0.345, 5486.778},           {206, 4.806, 2544.314},
    {205, 1.869, 5573.143},      {202, 2.458, 6069.777},           {156, 0.833, 213.299},
    {132, 3.411, 2942.463},      {126, 1.083, 20.775},             {115, 0.645, 0.98},
    {103, 0.636, 4694.003},      {102, 0.976, 15720.839},          {102, 4.267, 7.114},
    {99, 6.21, 2146.17},         {98, 0.68, 155.42},               {86, 5.98, 161000.69},
    {85, 1.3, 6275.96},          {85, 3.67, 71430.7},              {80, 1.81, 17260.15},
    {79, 3.04, 12036.46},        {75, 1.76, 5088.63},              {74, 3.5, 3154.69},
    {74, 4.68, 801.82},          {70, 0.83, 9437.76},              {62, 3.98, 8827.39},
    {61, 1.82, 7084.9},          {57, 2.78, 6286.6},               {56, 4.39, 14143.5},
    {56, 3.47, 6279.55},         {52, 0.19, 12139.55},             {52, 1.33, 1748.02},
    {51, 0.28, 5856.48},         {49, 0.49, 1194.45},              {41, 5.37, 8429.24},
    {41, 2.4, 19651.05},         {39, 6.17, 10447.39},             {37, 6.04, 10213.29},
    {37, 2.57, 1059.38},         {36, 1.71, 2352.87},              {36, 1.78, 6812.77},
    {33, 0.59, 17789.85},        {30, 0.44, 83996.85},             {30, 2.74, 1349.87},
    {25, 3.16, 4690.48},
};
constexpr PeriodicTerm kL1[] = {
    {628331966747, 0, 0}, {206059, 2.678235, 6283.07585}, {4303, 2.6351, 12566.1517},
    {425, 1.59, 3.523},   {119, 5.796, 26.298},           {109, 2.966, 1577.344},
    {93, 2.59, 18849.23}, {72, 1.14, 529.69},             {68, 1.87, 398.15},
    {67, 4.41, 5507.55},  {59, 2.89, 5223.69},            {56, 2.17, 155.42},
    {45, 0.4, 796.3},     {36, 0.47, 775.52},             {29, 2.65, 7.11},
    {21, 5.34, 0.98},     {19, 1.85, 5486.78},            {19, 4.97, 213.3},
    {17, 2.99, 6275.96},  {16, 0.03, 2544.31},            {16, 1.43, 2146.17},
    {15, 1.21, 10977.08}, {12, 2.83, 1748.02},            {12, 3.26, 5088.63},
    {12, 5.27, 1194.45},  {12, 2.08, 4694},               {11, 0.77, 553.57},
    {10, 1.3, 6286.6},    {10, 4.24, 1349.87},            {9, 2.7, 242.73},
    {9, 5.64, 951.72},    {8, 5.3, 2352.87},              {6, 2.65, 9437.76},
    {6, 4.67, 4690.48},
};
constexpr PeriodicTerm kL2[] = {
    {52919, 0, 0},     {8720, 1.0721, 6283.0758}, {309, 0.867, 12566.152}, {27, 0.05, 3.52},
    {16, 5.19, 26.3},  {16, 3.68, 155.42},        {10, 0.76, 18849.23},    {9, 2.06, 77713.77},
    {7, 0.83, 775.52}, {5, 4.66, 1577.34},        {4, 1.03, 7.11},         {4, 3.44, 5573.14},
    {3, 5.14, 796.3},  {3, 6.05, 5507.55},        {3, 1.19, 242.73},       {3, 6.12, 529.69},
    {3, 0.31, 398.15}, {3, 2.28, 553.57},         {2, 4.38, 5223.69},      {2, 3.75, 0.98},
};
constexpr PeriodicTerm kL3[] = {
    {289, 5.844, 6283.076}, {35, 0, 0},          {17, 5.49, 12566.15}, {3, 5.2, 155.42},
    {1, 4.72, 3.52},        {1, 5.3, 18849.23},  {1, 5.97, 242.73},
};
constexpr PeriodicTerm kL4[] = {{114, 3.142, 0}, {8, 4.13, 6283.08}, {1, 3.84, 12566.15}};
constexpr PeriodicTerm kL5[] = {{1, 3.14, 0}};

constexpr PeriodicTerm kB0[] = {
    {280, 3.199, 84334.662}, {102, 5.422, 5507.553}, {80, 3.88, 5223.69},
    {44, 3.7, 2352.87},      {32, 4, 1577.34},
};
constexpr PeriodicTerm kB1[] = {{9, 3.9, 5507.55}, {6, 1.73, 5223.69}};

constexpr PeriodicTerm kR0[] = {
    {100013989, 0, 0},        {1670700, 3.0984635, 6283.07585}, {13956, 3.05525, 12566.1517},
    {3084, 5.1985, 77713.7715}, {1628, 1.1739, 5753.3849},      {1576, 2.8469, 7860.4194},
    {925, 5.453, 11506.77},   {542, 4.564, 3930.21},            {472, 3.661, 5884.927},
    {346, 0.964, 5507.553},   {329, 5.9, 5223.694},             {307, 0.299, 5573.143},
    {243, 4.273, 11790.629},  {212, 5.847, 1577.344},           {186, 5.022, 10977.079},
    {175, 3.012, 18849.228},  {110, 5.055, 5486.778},           {98, 0.89, 6069.78},
    {86, 5.69, 15720.84},     {86, 1.27, 161000.69},            {65, 0.27, 17260.15},
    {63, 0.92, 529.69},       {57, 2.01, 83996.85},             {56, 5.24, 71430.7},
    {49, 3.25, 2544.31},      {47, 2.58, 775.52},               {45, 5.54, 9437.76},
    {43, 6.01, 6275.96},      {39, 5.36, 4694},                 {38, 2.39, 8827.39},
    {37, 0.83, 19651.05},     {37, 4.9, 12139.55},              {36, 1.67, 12036.46},
    {35, 1.84, 2942.46},      {33, 0.24, 7084.9},               {32, 0.18, 5088.63},
    {32, 1.78, 398.15},       {28, 1.21, 6286.6},               {28, 1.9, 6279.55},
    {26, 4.59, 10447.39},
};
constexpr PeriodicTerm kR1[] = {
    {103019, 1.10749, 6283.07585}, {1721, 1.0644, 12566.1517}, {702, 3.142, 0},
    {32, 1.02, 18849.23},          {31, 2.84, 5507.55},        {25, 1.32, 5223.69},
    {18, 1.42, 1577.34},           {10, 5.91, 10977.08},       {9, 1.42, 6275.96},
    {9, 0.27, 5486.78},
};
constexpr PeriodicTerm kR2[] = {
    {4359, 5.7846, 6283.0758}, {124, 5.579, 12566.152}, {12, 3.14, 0},
    {9, 3.63, 77713.77},       {6, 1.87, 5573.14},      {3, 5.47, 18849.23},
};
constexpr PeriodicTerm kR3[] = {{145, 4.273, 6283.076}, {7, 3.92, 12566.15}};
constexpr PeriodicTerm kR4[] = {{4, 2.56, 6283.08}};

// --- Nutation (report Table A4.3): multiples Y0..Y4 of X0..X4, and coefficients a, b, c, d ---

struct NutationTerm {
    signed char y[5];
    double a, b, c, d;  // Δψ = (a + b·JCE) sin(·), Δε = (c + d·JCE) cos(·), units 0.0001″
};

constexpr NutationTerm kNutation[] = {
    {{0, 0, 0, 0, 1}, -171996, -174.2, 92025, 8.9},
    {{-2, 0, 0, 2, 2}, -13187, -1.6, 5736, -3.1},
    {{0, 0, 0, 2, 2}, -2274, -0.2, 977, -0.5},
    {{0, 0, 0, 0, 2}, 2062, 0.2, -895, 0.5},
    {{0, 1, 0, 0, 0}, 1426, -3.4, 54, -0.1},
    {{0, 0, 1, 0, 0}, 712, 0.1, -7, 0},
    {{-2, 1, 0, 2, 2}, -517, 1.2, 224, -0.6},
    {{0, 0, 0, 2, 1}, -386, -0.4, 200, 0},
    {{0, 0, 1, 2, 2}, -301, 0, 129, -0.1},
    {{-2, -1, 0, 2, 2}, 217, -0.5, -95, 0.3},
    {{-2, 0, 1, 0, 0}, -158, 0, 0, 0},
    {{-2, 0, 0, 2, 1}, 129, 0.1, -70, 0},
    {{0, 0, -1, 2, 2}, 123, 0, -53, 0},
    {{2, 0, 0, 0, 0}, 63, 0, 0, 0},
    {{0, 0, 1, 0, 1}, 63, 0.1, -33, 0},
    {{2, 0, -1, 2, 2}, -59, 0, 26, 0},
    {{0, 0, -1, 0, 1}, -58, -0.1, 32, 0},
    {{0, 0, 1, 2, 1}, -51, 0, 27, 0},
    {{-2, 0, 2, 0, 0}, 48, 0, 0, 0},
    {{0, 0, -2, 2, 1}, 46, 0, -24, 0},
    {{2, 0, 0, 2, 2}, -38, 0, 16, 0},
    {{0, 0, 2, 2, 2}, -31, 0, 13, 0},
    {{0, 0, 2, 0, 0}, 29, 0, 0, 0},
    {{-2, 0, 1, 2, 2}, 29, 0, -12, 0},
    {{0, 0, 0, 2, 0}, 26, 0, 0, 0},
    {{-2, 0, 0, 2, 0}, -22, 0, 0, 0},
    {{0, 0, -1, 2, 1}, 21, 0, -10, 0},
    {{0, 2, 0, 0, 0}, 17, -0.1, 0, 0},
    {{2, 0, -1, 0, 1}, 16, 0, -8, 0},
    {{-2, 2, 0, 2, 2}, -16, 0.1, 7, 0},
    {{0, 1, 0, 0, 1}, -15, 0, 9, 0},
    {{-2, 0, 1, 0, 1}, -13, 0, 7, 0},
    {{0, -1, 0, 0, 1}, -12, 0, 6, 0},
    {{0, 0, 2, -2, 0}, 11, 0, 0, 0},
    {{2, 0, -1, 2, 1}, -10, 0, 5, 0},
    {{2, 0, 1, 2, 2}, -8, 0, 3, 0},
    {{0, 1, 0, 2, 2}, 7, 0, -3, 0},
    {{-2, 1, 1, 0, 0}, -7, 0, 0, 0},
    {{0, -1, 0, 2, 2}, -7, 0, 3, 0},
    {{2, 0, 0, 2, 1}, -7, 0, 3, 0},
    {{2, 0, 1, 0, 0}, 6, 0, 0, 0},
    {{-2, 0, 2, 2, 2}, 6, 0, -3, 0},
    {{-2, 0, 1, 2, 1}, 6, 0, -3, 0},
    {{2, 0, -2, 0, 1}, -6, 0, 3, 0},
    {{2, 0, 0, 0, 1}, -6, 0, 3, 0},
    {{0, -1, 1, 0, 0}, 5, 0, 0, 0},
    {{-2, -1, 0, 2, 1}, -5, 0, 3, 0},
    {{-2, 0, 0, 0, 1}, -5, 0, 3, 0},
    {{0, 0, 2, 2, 1}, -5, 0, 3, 0},
    {{-2, 0, 2, 0, 1}, 4, 0, 0, 0},
    {{-2, 1, 0, 2, 1}, 4, 0, 0, 0},
    {{0, 0, 1, -2, 0}, 4, 0, 0, 0},
    {{-1, 0, 1, 0, 0}, -4, 0, 0, 0},
    {{-2, 1, 0, 0, 0}, -4, 0, 0, 0},
    {{1, 0, 0, 0, 0}, -4, 0, 0, 0},
    {{0, 0, 1, 2, 0}, 3, 0, 0, 0},
    {{0, 0, -2, 2, 2}, -3, 0, 0, 0},
    {{-1, -1, 1, 0, 0}, -3, 0, 0, 0},
    {{0, 1, 1, 0, 0}, -3, 0, 0, 0},
    {{0, -1, 1, 2, 2}, -3, 0, 0, 0},
    {{2, -1, -1, 2, 2}, -3, 0, 0, 0},
    {{0, 0, 3, 2, 2}, -3, 0, 0, 0},
    {{2, -1, 0, 2, 2}, -3, 0, 0, 0},
};
static_assert(std::size(kNutation) == 63, "SPA Table A4.3 has 63 rows");

/// Σ A cos(B + C·JME) of one table (Eq. 9).
double termSum(std::span<const PeriodicTerm> terms, double jme) {
    double sum = 0;
    for (const PeriodicTerm& t : terms) sum += t.a * std::cos(t.b + t.c * jme);
    return sum;
}

/// (X0 + X1·JME + X2·JME² + ...) / 1e8 of a family of tables (Eq. 10-11).
template <std::size_t N>
double seriesValue(const std::array<std::span<const PeriodicTerm>, N>& tables, double jme) {
    double value = 0;
    for (std::size_t i = N; i-- > 0;) value = value * jme + termSum(tables[i], jme);
    return value / 1e8;
}

const std::array<std::span<const PeriodicTerm>, 6> kLTables{kL0, kL1, kL2, kL3, kL4, kL5};
const std::array<std::span<const PeriodicTerm>, 2> kBTables{kB0, kB1};
const std::array<std::span<const PeriodicTerm>, 5> kRTables{kR0, kR1, kR2, kR3, kR4};

double polynomial3(double c0, double c1, double c2, double c3inv, double x) {
    return c0 + x * (c1 + x * (c2 + x / c3inv));
}

struct Nutation {
    double longitudeDeg;  // Δψ
    double obliquityDeg;  // Δε
};

/// Nutation in longitude and obliquity (Eq. 15-22).
Nutation nutation(double jce) {
    const double x[5] = {
        polynomial3(297.85036, 445267.111480, -0.0019142, 189474.0, jce),   // mean elongation moon-sun
        polynomial3(357.52772, 35999.050340, -0.0001603, -300000.0, jce),   // mean anomaly sun
        polynomial3(134.96298, 477198.867398, 0.0086972, 56250.0, jce),     // mean anomaly moon
        polynomial3(93.27191, 483202.017538, -0.0036825, 327270.0, jce),    // moon arg. of latitude
        polynomial3(125.04452, -1934.136261, 0.0020708, 450000.0, jce),     // moon ascending node
    };
    double dPsi = 0, dEps = 0;
    for (const NutationTerm& t : kNutation) {
        double arg = 0;
        for (int j = 0; j < 5; ++j) arg += x[j] * t.y[j];
        arg = rad(arg);
        dPsi += (t.a + t.b * jce) * std::sin(arg);
        dEps += (t.c + t.d * jce) * std::cos(arg);
    }
    constexpr double kUnitsPerDeg = 36000000.0;  // 0.0001 arcsec
    return {dPsi / kUnitsPerDeg, dEps / kUnitsPerDeg};
}

/// Mean obliquity of the ecliptic ε0 (arc seconds), Eq. 24.
double meanObliquityArcsec(double jme) {
    constexpr double c[] = {84381.448, -4680.93, -1.55, 1999.25, -51.38, -249.67,
                            -39.05,    7.12,     27.87, 5.79,    2.45};
    const double u = jme / 10.0;
    double value = 0;
    for (std::size_t i = std::size(c); i-- > 0;) value = value * u + c[i];
    return value;
}

/// Geocentric apparent sun at one Julian Ephemeris Day and the Greenwich apparent sidereal
/// time at the matching Julian Day (Eq. 4-34 up to the hour angle).
struct Geocentric {
    double jme;
    double lDeg, bDeg, rAu;
    double thetaDeg, betaDeg;
    Nutation nut;
    double epsilonDeg, aberrationDeg, lambdaDeg;
    double nuDeg;     // apparent sidereal time at Greenwich
    double alphaDeg;  // right ascension [0, 360)
    double deltaDeg;  // declination
};

Geocentric geocentricSun(double jd, double jde) {
    Geocentric g{};
    const double jc = (jd - kJ2000) / kDaysPerCentury;     // Eq. 5
    const double jce = (jde - kJ2000) / kDaysPerCentury;   // Eq. 6
    g.jme = jce / 10.0;                                     // Eq. 7

    // Earth heliocentric longitude, latitude, radius vector (Eq. 9-13).
    g.lDeg = wrap360(deg(seriesValue(kLTables, g.jme)));
    g.bDeg = deg(seriesValue(kBTables, g.jme));
    g.rAu = seriesValue(kRTables, g.jme);

    // Geocentric longitude and latitude (Eq. 13-14).
    g.thetaDeg = wrap360(g.lDeg + 180.0);
    g.betaDeg = -g.bDeg;

    g.nut = nutation(jce);
    g.epsilonDeg = meanObliquityArcsec(g.jme) / 3600.0 + g.nut.obliquityDeg;  // Eq. 25
    g.aberrationDeg = -20.4898 / (3600.0 * g.rAu);                            // Eq. 26
    g.lambdaDeg = g.thetaDeg + g.nut.longitudeDeg + g.aberrationDeg;          // Eq. 27

    // Apparent sidereal time at Greenwich (Eq. 28-29).
    const double nu0 = wrap360(280.46061837 + 360.98564736629 * (jd - kJ2000) +
                               jc * jc * (0.000387933 - jc / 38710000.0));
    g.nuDeg = nu0 + g.nut.longitudeDeg * std::cos(rad(g.epsilonDeg));

    // Geocentric right ascension and declination (Eq. 30-31).
    const double lambda = rad(g.lambdaDeg), eps = rad(g.epsilonDeg), beta = rad(g.betaDeg);
    g.alphaDeg = wrap360(deg(std::atan2(std::sin(lambda) * std::cos(eps) -
                                            std::tan(beta) * std::sin(eps),
                                        std::cos(lambda))));
    g.deltaDeg = deg(std::asin(std::sin(beta) * std::cos(eps) +
                               std::cos(beta) * std::sin(eps) * std::sin(lambda)));
    return g;
}

/// Equation of time (minutes), report A.1 Eq. A1-A4.
double equationOfTimeMin(const Geocentric& g) {
    const double jme = g.jme;
    const double m = 280.4664567 +
                     jme * (360007.6982779 +
                            jme * (0.03032028 +
                                   jme * (1.0 / 49931.0 + jme * (-1.0 / 15300.0 - jme / 2000000.0))));
    const double e =
        m - 0.0057183 - g.alphaDeg + g.nut.longitudeDeg * std::cos(rad(g.epsilonDeg));
    constexpr double kMinutesPerDeg = 4.0;
    return wrap180(e) * kMinutesPerDeg;  // |E| stays below 20 min
}

/// Refraction correction Δe (degrees) for a geometric elevation e0 (Eq. 42), applied only while
/// the sun can be above the refracted horizon.
double refractionDeg(double e0Deg, const SolarSite& site, const SpaOptions& options) {
    if (site.pressureHpa <= 0) return 0;
    if (e0Deg < -(options.sunRadiusDeg + options.horizonRefractionDeg)) return 0;
    constexpr double kStandardPressureHpa = 1010.0, kStandardTemperatureK = 283.0;
    return (site.pressureHpa / kStandardPressureHpa) *
           (kStandardTemperatureK / (273.0 + site.temperatureC)) * 1.02 /
           (60.0 * std::tan(rad(e0Deg + 10.3 / (e0Deg + 5.11))));
}

double deltaTFor(UtcInstant t, const SpaOptions& options) {
    return options.deltaTSec ? *options.deltaTSec : deltaTSeconds(decimalYear(t));
}

}  // namespace

void checkSpaValidity(UtcInstant t) {
    const int year = static_cast<int>(std::chrono::year_month_day{std::chrono::floor<std::chrono::days>(t)}.year());
    if (year < kSpaFirstYear || year > kSpaLastYear)
        throw Error("time " + formatInstant(t, TimeZoneSpec{}) + ": outside the years " + std::to_string(kSpaFirstYear) +
                    " to " + std::to_string(kSpaLastYear) + " the solar position algorithm (NREL SPA) is valid for");
}

SolarPosition solarPosition(const SolarSite& site, UtcInstant t, const SpaOptions& options,
                            SpaTrace* trace) {
    checkSpaValidity(t);
    const double deltaT = deltaTFor(t, options);
    const double jd = julianDay(t);                      // Eq. 4 (from the Unix clock)
    const double jde = jd + deltaT / kSecondsPerDay;    // Eq. 5
    const Geocentric g = geocentricSun(jd, jde);

    // Observer local hour angle (Eq. 32).
    const double hDeg = wrap360(g.nuDeg + site.longitudeDeg - g.alphaDeg);

    // Topocentric parallax (Eq. 33-38).
    const double xiDeg = 8.794 / (3600.0 * g.rAu);
    const double phi = rad(site.latitudeDeg);
    const double u = std::atan(kEarthPolarRatio * std::tan(phi));
    const double heightRatio = site.elevationM / kEarthEquatorialRadiusM;
    const double x = std::cos(u) + heightRatio * std::cos(phi);
    const double y = kEarthPolarRatio * std::sin(u) + heightRatio * std::sin(phi);
    const double xi = rad(xiDeg), h = rad(hDeg), delta = rad(g.deltaDeg);
    const double denom = std::cos(delta) - x * std::sin(xi) * std::cos(h);
    const double dAlpha = std::atan2(-x * std::sin(xi) * std::sin(h), denom);
    const double deltaPrime =
        std::atan2((std::sin(delta) - y * std::sin(xi)) * std::cos(dAlpha), denom);
    const double hPrime = h - dAlpha;  // Eq. 40

    // Topocentric elevation, refraction, zenith (Eq. 41-44).
    const double e0Deg = deg(std::asin(std::sin(phi) * std::sin(deltaPrime) +
                                       std::cos(phi) * std::cos(deltaPrime) * std::cos(hPrime)));
    const double de = refractionDeg(e0Deg, site, options);
    const double eDeg = e0Deg + de;

    // Topocentric azimuth (Eq. 45-47), astronomers' (from south) turned to from north.
    const double gammaDeg = deg(std::atan2(
        std::sin(hPrime), std::cos(hPrime) * std::sin(phi) - std::tan(deltaPrime) * std::cos(phi)));

    SolarPosition p{};
    p.zenithDeg = 90.0 - eDeg;
    p.elevationDeg = eDeg;
    p.azimuthDeg = wrap360(gammaDeg + 180.0);
    p.geometricElevationDeg = e0Deg;
    p.refractionDeg = de;
    p.rightAscensionDeg = wrap360(g.alphaDeg + deg(dAlpha));
    p.declinationDeg = deg(deltaPrime);
    p.hourAngleDeg = wrap360(deg(hPrime));
    p.equationOfTimeMin = equationOfTimeMin(g);
    p.deltaTSec = deltaT;

    if (trace) {
        *trace = SpaTrace{jd,
                          jde,
                          g.jme,
                          g.lDeg,
                          g.bDeg,
                          g.rAu,
                          g.thetaDeg,
                          g.betaDeg,
                          g.nut.longitudeDeg,
                          g.nut.obliquityDeg,
                          g.epsilonDeg,
                          g.aberrationDeg,
                          g.lambdaDeg,
                          g.nuDeg,
                          g.alphaDeg,
                          g.deltaDeg,
                          hDeg,
                          xiDeg,
                          deg(dAlpha)};
    }
    return p;
}

SunEvents sunEvents(const SolarSite& site, UtcInstant dayStartUtc, const SpaOptions& options) {
    checkSpaValidity(dayStartUtc);
    // SPA appendix A.2, with the day's origin at dayStartUtc instead of 0 h UT.
    const double deltaT = deltaTFor(dayStartUtc, options);
    const double jd0 = julianDay(dayStartUtc);

    // A.2.1: apparent sidereal time at the origin (ΔT = 0).
    const double nu = geocentricSun(jd0, jd0).nuDeg;
    // A.2.2: geocentric α, δ at the origin taken as TT, for the day before, the day, the day after.
    double alpha[3], delta[3];
    for (int i = 0; i < 3; ++i) {
        const Geocentric g = geocentricSun(jd0 + i - 1, jd0 + i - 1);
        alpha[i] = g.alphaDeg;
        delta[i] = g.deltaDeg;
    }

    const double phi = rad(site.latitudeDeg);
    const double sigma = site.longitudeDeg;
    const double h0Prime = -(options.sunRadiusDeg + options.horizonRefractionDeg);  // −0.8333°

    // A.2.3: approximate transit time (fraction of a day).
    const double m0 = (alpha[1] - sigma - nu) / 360.0;
    // A.2.4: local hour angle of rise/set; outside [-1, 1] the sun never crosses h0'.
    const double cosH0 = (std::sin(rad(h0Prime)) - std::sin(phi) * std::sin(rad(delta[1]))) /
                         (std::cos(phi) * std::cos(rad(delta[1])));

    SunEvents events;
    const bool crosses = std::abs(cosH0) <= 1.0;
    if (!crosses) events.kind = cosH0 > 1.0 ? DayKind::PolarNight : DayKind::PolarDay;
    const double h0Deg = crosses ? deg(std::acos(cosH0)) : 0.0;  // in [0, 180]

    // A.2.5-A.2.7: transit, rise, set fractions in [0, 1).
    const double m[3] = {wrapUnit(m0), wrapUnit(m0 - h0Deg / 360.0), wrapUnit(m0 + h0Deg / 360.0)};

    // A.2.10: interpolation coefficients. α changes about 1°/day; a difference near ±360° is
    // α wrapping through 0 (the report limits such values to [0, 1); reducing to [-180, 180)
    // gives the true difference whatever the daily rate).
    const double aA = wrap180(alpha[1] - alpha[0]), bA = wrap180(alpha[2] - alpha[1]);
    const double aD = delta[1] - delta[0], bD = delta[2] - delta[1];
    const double cA = bA - aA, cD = bD - aD;

    double hPrime[3], deltaPrime[3], hDeg[3];
    for (int i = 0; i < 3; ++i) {
        const double nuI = nu + 360.985647 * m[i];                 // A.2.8
        const double n = m[i] + deltaT / kSecondsPerDay;           // A.2.9
        const double alphaI = alpha[1] + n * (aA + bA + cA * n) / 2.0;  // A.2.10
        deltaPrime[i] = delta[1] + n * (aD + bD + cD * n) / 2.0;        // A.2.11
        hPrime[i] = wrap180(nuI + sigma - alphaI);                      // A.2.12
        hDeg[i] = deg(std::asin(std::sin(phi) * std::sin(rad(deltaPrime[i])) +
                                std::cos(phi) * std::cos(rad(deltaPrime[i])) *
                                    std::cos(rad(hPrime[i]))));          // A.2.13
    }

    const auto toInstant = [&dayStartUtc](double dayFraction) {
        return dayStartUtc + std::chrono::milliseconds(
                                 std::llround(dayFraction * kSecondsPerDay * 1000.0));
    };
    // A.2.14: transit.
    events.transit = toInstant(m[0] - hPrime[0] / 360.0);
    if (crosses) {
        // A.2.15-A.2.16: sunrise and sunset.
        const auto refine = [&](int i) {
            return m[i] + (hDeg[i] - h0Prime) / (360.0 * std::cos(rad(deltaPrime[i])) *
                                                 std::cos(phi) * std::sin(rad(hPrime[i])));
        };
        events.sunrise = toInstant(refine(1));
        events.sunset = toInstant(refine(2));
    }
    return events;
}

double deltaTSeconds(double y) {
    // Espenak & Meeus (2006), "Polynomial expressions for Delta T", NASA eclipse web site.
    const auto longTerm = [](double year) {
        const double u = (year - 1820.0) / 100.0;
        return -20.0 + 32.0 * u * u;
    };
    if (y < -500) return longTerm(y);
    if (y < 500) {
        const double u = y / 100.0;
        return 10583.6 + u * (-1014.41 + u * (33.78311 + u * (-5.952053 + u * (-0.1798452 +
                             u * (0.022174192 + u * 0.0090316521)))));
    }
    if (y < 1600) {
        const double u = (y - 1000.0) / 100.0;
        return 1574.2 + u * (-556.01 + u * (71.23472 + u * (0.319781 + u * (-0.8503463 +
                            u * (-0.005050998 + u * 0.0083572073)))));
    }
    if (y < 1700) {
        const double t = y - 1600.0;
        return 120.0 + t * (-0.9808 + t * (-0.01532 + t / 7129.0));
    }
    if (y < 1800) {
        const double t = y - 1700.0;
        return 8.83 + t * (0.1603 + t * (-0.0059285 + t * (0.00013336 - t / 1174000.0)));
    }
    if (y < 1860) {
        const double t = y - 1800.0;
        return 13.72 + t * (-0.332447 + t * (0.0068612 + t * (0.0041116 + t * (-0.00037436 +
                           t * (0.0000121272 + t * (-0.0000001699 + t * 0.000000000875))))));
    }
    if (y < 1900) {
        const double t = y - 1860.0;
        return 7.62 + t * (0.5737 + t * (-0.251754 + t * (0.01680668 + t * (-0.0004473624 +
                          t / 233174.0))));
    }
    if (y < 1920) {
        const double t = y - 1900.0;
        return -2.79 + t * (1.494119 + t * (-0.0598939 + t * (0.0061966 - t * 0.000197)));
    }
    if (y < 1941) {
        const double t = y - 1920.0;
        return 21.20 + t * (0.84493 + t * (-0.076100 + t * 0.0020936));
    }
    if (y < 1961) {
        const double t = y - 1950.0;
        return 29.07 + t * (0.407 + t * (-1.0 / 233.0 + t / 2547.0));
    }
    if (y < 1986) {
        const double t = y - 1975.0;
        return 45.45 + t * (1.067 + t * (-1.0 / 260.0 - t / 718.0));
    }
    if (y < 2005) {
        const double t = y - 2000.0;
        return 63.86 + t * (0.3345 + t * (-0.060374 + t * (0.0017275 + t * (0.000651814 +
                           t * 0.00002373599))));
    }
    if (y < 2050) {
        const double t = y - 2000.0;
        return 62.92 + t * (0.32217 + t * 0.005589);
    }
    if (y < 2150) return longTerm(y) - 0.5628 * (2150.0 - y);
    return longTerm(y);
}

}  // namespace demlight
