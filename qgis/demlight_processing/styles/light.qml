<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>
<qgis styleCategories="AllStyleCategories" maxScale="0" version="3.22.16-Białowieża" hasScaleBasedVisibilityFlag="0" minScale="1e+08">
  <flags>
    <Identifiable>1</Identifiable>
    <Removable>1</Removable>
    <Searchable>1</Searchable>
    <Private>0</Private>
  </flags>
  <temporal mode="0" fetchMode="0" enabled="0">
    <fixedRange>
      <start></start>
      <end></end>
    </fixedRange>
  </temporal>
  <customproperties>
    <Option type="Map">
      <Option name="identify/format" type="QString" value="Value"/>
    </Option>
  </customproperties>
  <pipe-data-defined-properties>
    <Option type="Map">
      <Option name="name" type="QString" value=""/>
      <Option name="properties"/>
      <Option name="type" type="QString" value="collection"/>
    </Option>
  </pipe-data-defined-properties>
  <pipe>
    <provider>
      <resampling maxOversampling="2" enabled="false" zoomedInResamplingMethod="nearestNeighbour" zoomedOutResamplingMethod="nearestNeighbour"/>
    </provider>
    <rasterrenderer alphaBand="-1" opacity="1" classificationMax="1" band="1" nodataColor="" type="singlebandpseudocolor" classificationMin="0">
      <minMaxOrigin>
        <limits>None</limits>
        <extent>WholeRaster</extent>
        <statAccuracy>Estimated</statAccuracy>
        <cumulativeCutLower>0.02</cumulativeCutLower>
        <cumulativeCutUpper>0.98</cumulativeCutUpper>
        <stdDevFactor>2</stdDevFactor>
      </minMaxOrigin>
      <rastershader>
        <colorrampshader clip="0" minimumValue="0" maximumValue="1" classificationMode="1" labelPrecision="6" colorRampType="INTERPOLATED">
          <colorramp name="[source]" type="gradient">
            <Option type="Map">
              <Option name="color1" type="QString" value="0,0,4,255"/>
              <Option name="color2" type="QString" value="252,253,191,255"/>
              <Option name="discrete" type="QString" value="0"/>
              <Option name="rampType" type="QString" value="gradient"/>
              <Option name="stops" type="QString" value="0.0196078;2,2,11,255:0.0392157;5,4,22,255:0.0588235;9,7,32,255:0.0784314;14,11,43,255:0.0980392;20,14,54,255:0.117647;26,16,66,255:0.137255;33,17,78,255:0.156863;41,17,90,255:0.176471;49,17,101,255:0.196078;57,15,110,255:0.215686;66,15,117,255:0.235294;74,16,121,255:0.254902;82,19,124,255:0.27451;90,22,126,255:0.294118;98,25,128,255:0.313725;106,28,129,255:0.333333;114,31,129,255:0.352941;121,34,130,255:0.372549;129,37,129,255:0.392157;137,40,129,255:0.411765;145,43,129,255:0.431373;153,45,128,255:0.45098;161,48,126,255:0.470588;170,51,125,255:0.490196;178,53,123,255:0.509804;186,56,120,255:0.529412;194,59,117,255:0.54902;202,62,114,255:0.568627;210,66,111,255:0.588235;217,70,107,255:0.607843;224,76,103,255:0.627451;231,82,99,255:0.647059;236,88,96,255:0.666667;241,96,93,255:0.686275;244,105,92,255:0.705882;247,114,92,255:0.72549;249,123,93,255:0.745098;251,133,96,255:0.764706;252,142,100,255:0.784314;253,152,105,255:0.803922;254,161,110,255:0.823529;254,170,116,255:0.843137;254,180,123,255:0.862745;254,189,130,255:0.882353;254,198,138,255:0.901961;254,207,146,255:0.921569;254,216,154,255:0.941176;253,226,163,255:0.960784;253,235,172,255:0.980392;252,244,182,255"/>
            </Option>
            <prop v="0,0,4,255" k="color1"/>
            <prop v="252,253,191,255" k="color2"/>
            <prop v="0" k="discrete"/>
            <prop v="gradient" k="rampType"/>
            <prop v="0.0196078;2,2,11,255:0.0392157;5,4,22,255:0.0588235;9,7,32,255:0.0784314;14,11,43,255:0.0980392;20,14,54,255:0.117647;26,16,66,255:0.137255;33,17,78,255:0.156863;41,17,90,255:0.176471;49,17,101,255:0.196078;57,15,110,255:0.215686;66,15,117,255:0.235294;74,16,121,255:0.254902;82,19,124,255:0.27451;90,22,126,255:0.294118;98,25,128,255:0.313725;106,28,129,255:0.333333;114,31,129,255:0.352941;121,34,130,255:0.372549;129,37,129,255:0.392157;137,40,129,255:0.411765;145,43,129,255:0.431373;153,45,128,255:0.45098;161,48,126,255:0.470588;170,51,125,255:0.490196;178,53,123,255:0.509804;186,56,120,255:0.529412;194,59,117,255:0.54902;202,62,114,255:0.568627;210,66,111,255:0.588235;217,70,107,255:0.607843;224,76,103,255:0.627451;231,82,99,255:0.647059;236,88,96,255:0.666667;241,96,93,255:0.686275;244,105,92,255:0.705882;247,114,92,255:0.72549;249,123,93,255:0.745098;251,133,96,255:0.764706;252,142,100,255:0.784314;253,152,105,255:0.803922;254,161,110,255:0.823529;254,170,116,255:0.843137;254,180,123,255:0.862745;254,189,130,255:0.882353;254,198,138,255:0.901961;254,207,146,255:0.921569;254,216,154,255:0.941176;253,226,163,255:0.960784;253,235,172,255:0.980392;252,244,182,255" k="stops"/>
          </colorramp>
          <item label="0" color="#000004" value="0" alpha="255"/>
          <item label="0.0196" color="#02020b" value="0.0196078" alpha="255"/>
          <item label="0.0392" color="#050416" value="0.0392157" alpha="255"/>
          <item label="0.0588" color="#090720" value="0.0588235" alpha="255"/>
          <item label="0.0784" color="#0e0b2b" value="0.0784314" alpha="255"/>
          <item label="0.098" color="#140e36" value="0.0980392" alpha="255"/>
          <item label="0.118" color="#1a1042" value="0.117647" alpha="255"/>
          <item label="0.137" color="#21114e" value="0.137255" alpha="255"/>
          <item label="0.157" color="#29115a" value="0.156863" alpha="255"/>
          <item label="0.176" color="#311165" value="0.176471" alpha="255"/>
          <item label="0.196" color="#390f6e" value="0.196078" alpha="255"/>
          <item label="0.216" color="#420f75" value="0.215686" alpha="255"/>
          <item label="0.235" color="#4a1079" value="0.235294" alpha="255"/>
          <item label="0.255" color="#52137c" value="0.254902" alpha="255"/>
          <item label="0.275" color="#5a167e" value="0.27451" alpha="255"/>
          <item label="0.294" color="#621980" value="0.294118" alpha="255"/>
          <item label="0.314" color="#6a1c81" value="0.313725" alpha="255"/>
          <item label="0.333" color="#721f81" value="0.333333" alpha="255"/>
          <item label="0.353" color="#792282" value="0.352941" alpha="255"/>
          <item label="0.373" color="#812581" value="0.372549" alpha="255"/>
          <item label="0.392" color="#892881" value="0.392157" alpha="255"/>
          <item label="0.412" color="#912b81" value="0.411765" alpha="255"/>
          <item label="0.431" color="#992d80" value="0.431373" alpha="255"/>
          <item label="0.451" color="#a1307e" value="0.45098" alpha="255"/>
          <item label="0.471" color="#aa337d" value="0.470588" alpha="255"/>
          <item label="0.49" color="#b2357b" value="0.490196" alpha="255"/>
          <item label="0.51" color="#ba3878" value="0.509804" alpha="255"/>
          <item label="0.529" color="#c23b75" value="0.529412" alpha="255"/>
          <item label="0.549" color="#ca3e72" value="0.54902" alpha="255"/>
          <item label="0.569" color="#d2426f" value="0.568627" alpha="255"/>
          <item label="0.588" color="#d9466b" value="0.588235" alpha="255"/>
          <item label="0.608" color="#e04c67" value="0.607843" alpha="255"/>
          <item label="0.627" color="#e75263" value="0.627451" alpha="255"/>
          <item label="0.647" color="#ec5860" value="0.647059" alpha="255"/>
          <item label="0.667" color="#f1605d" value="0.666667" alpha="255"/>
          <item label="0.686" color="#f4695c" value="0.686275" alpha="255"/>
          <item label="0.706" color="#f7725c" value="0.705882" alpha="255"/>
          <item label="0.725" color="#f97b5d" value="0.72549" alpha="255"/>
          <item label="0.745" color="#fb8560" value="0.745098" alpha="255"/>
          <item label="0.765" color="#fc8e64" value="0.764706" alpha="255"/>
          <item label="0.784" color="#fd9869" value="0.784314" alpha="255"/>
          <item label="0.804" color="#fea16e" value="0.803922" alpha="255"/>
          <item label="0.824" color="#feaa74" value="0.823529" alpha="255"/>
          <item label="0.843" color="#feb47b" value="0.843137" alpha="255"/>
          <item label="0.863" color="#febd82" value="0.862745" alpha="255"/>
          <item label="0.882" color="#fec68a" value="0.882353" alpha="255"/>
          <item label="0.902" color="#fecf92" value="0.901961" alpha="255"/>
          <item label="0.922" color="#fed89a" value="0.921569" alpha="255"/>
          <item label="0.941" color="#fde2a3" value="0.941176" alpha="255"/>
          <item label="0.961" color="#fdebac" value="0.960784" alpha="255"/>
          <item label="0.98" color="#fcf4b6" value="0.980392" alpha="255"/>
          <item label="1" color="#fcfdbf" value="1" alpha="255"/>
          <rampLegendSettings maximumLabel="" orientation="2" direction="0" useContinuousLegend="1" suffix="" prefix="" minimumLabel="">
            <numericFormat id="basic">
              <Option type="Map">
                <Option name="decimal_separator" type="QChar" value=""/>
                <Option name="decimals" type="int" value="6"/>
                <Option name="rounding_type" type="int" value="0"/>
                <Option name="show_plus" type="bool" value="false"/>
                <Option name="show_thousand_separator" type="bool" value="true"/>
                <Option name="show_trailing_zeros" type="bool" value="false"/>
                <Option name="thousand_separator" type="QChar" value=""/>
              </Option>
            </numericFormat>
          </rampLegendSettings>
        </colorrampshader>
      </rastershader>
    </rasterrenderer>
    <brightnesscontrast contrast="0" gamma="1" brightness="0"/>
    <huesaturation colorizeStrength="100" colorizeRed="255" colorizeOn="0" invertColors="0" colorizeBlue="128" colorizeGreen="128" saturation="0" grayscaleMode="0"/>
    <rasterresampler maxOversampling="2"/>
    <resamplingStage>resamplingFilter</resamplingStage>
  </pipe>
  <blendMode>0</blendMode>
</qgis>
