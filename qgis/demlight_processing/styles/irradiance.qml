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
    <rasterrenderer alphaBand="-1" opacity="1" classificationMax="1000" band="4" nodataColor="" type="singlebandpseudocolor" classificationMin="0">
      <minMaxOrigin>
        <limits>None</limits>
        <extent>WholeRaster</extent>
        <statAccuracy>Estimated</statAccuracy>
        <cumulativeCutLower>0.02</cumulativeCutLower>
        <cumulativeCutUpper>0.98</cumulativeCutUpper>
        <stdDevFactor>2</stdDevFactor>
      </minMaxOrigin>
      <rastershader>
        <colorrampshader clip="0" minimumValue="0" maximumValue="1000" classificationMode="1" labelPrecision="6" colorRampType="INTERPOLATED">
          <colorramp name="[source]" type="gradient">
            <Option type="Map">
              <Option name="color1" type="QString" value="0,0,4,255"/>
              <Option name="color2" type="QString" value="252,255,164,255"/>
              <Option name="discrete" type="QString" value="0"/>
              <Option name="rampType" type="QString" value="gradient"/>
              <Option name="stops" type="QString" value="0.0196078;2,2,12,255:0.0392157;5,4,23,255:0.0588235;10,7,34,255:0.0784314;16,9,45,255:0.0980392;22,11,57,255:0.117647;30,12,69,255:0.137255;38,12,81,255:0.156863;47,10,91,255:0.176471;56,9,98,255:0.196078;64,10,103,255:0.215686;73,11,106,255:0.235294;81,14,108,255:0.254902;89,16,110,255:0.27451;97,19,110,255:0.294118;105,22,110,255:0.313725;113,25,110,255:0.333333;120,28,109,255:0.352941;128,31,108,255:0.372549;136,34,106,255:0.392157;144,37,104,255:0.411765;152,39,102,255:0.431373;160,42,99,255:0.45098;168,46,95,255:0.470588;176,49,91,255:0.490196;183,53,87,255:0.509804;191,57,82,255:0.529412;198,61,77,255:0.54902;204,66,72,255:0.568627;211,71,67,255:0.588235;217,77,61,255:0.607843;223,83,55,255:0.627451;228,90,49,255:0.647059;233,97,43,255:0.666667;237,105,37,255:0.686275;241,113,31,255:0.705882;244,121,24,255:0.72549;247,130,18,255:0.745098;249,139,11,255:0.764706;250,148,7,255:0.784314;251,157,7,255:0.803922;252,166,12,255:0.823529;252,176,20,255:0.843137;251,186,31,255:0.862745;250,196,42,255:0.882353;248,205,55,255:0.901961;246,215,70,255:0.921569;244,225,86,255:0.941176;242,234,105,255:0.960784;242,242,125,255:0.980392;245,249,146,255"/>
            </Option>
            <prop v="0,0,4,255" k="color1"/>
            <prop v="252,255,164,255" k="color2"/>
            <prop v="0" k="discrete"/>
            <prop v="gradient" k="rampType"/>
            <prop v="0.0196078;2,2,12,255:0.0392157;5,4,23,255:0.0588235;10,7,34,255:0.0784314;16,9,45,255:0.0980392;22,11,57,255:0.117647;30,12,69,255:0.137255;38,12,81,255:0.156863;47,10,91,255:0.176471;56,9,98,255:0.196078;64,10,103,255:0.215686;73,11,106,255:0.235294;81,14,108,255:0.254902;89,16,110,255:0.27451;97,19,110,255:0.294118;105,22,110,255:0.313725;113,25,110,255:0.333333;120,28,109,255:0.352941;128,31,108,255:0.372549;136,34,106,255:0.392157;144,37,104,255:0.411765;152,39,102,255:0.431373;160,42,99,255:0.45098;168,46,95,255:0.470588;176,49,91,255:0.490196;183,53,87,255:0.509804;191,57,82,255:0.529412;198,61,77,255:0.54902;204,66,72,255:0.568627;211,71,67,255:0.588235;217,77,61,255:0.607843;223,83,55,255:0.627451;228,90,49,255:0.647059;233,97,43,255:0.666667;237,105,37,255:0.686275;241,113,31,255:0.705882;244,121,24,255:0.72549;247,130,18,255:0.745098;249,139,11,255:0.764706;250,148,7,255:0.784314;251,157,7,255:0.803922;252,166,12,255:0.823529;252,176,20,255:0.843137;251,186,31,255:0.862745;250,196,42,255:0.882353;248,205,55,255:0.901961;246,215,70,255:0.921569;244,225,86,255:0.941176;242,234,105,255:0.960784;242,242,125,255:0.980392;245,249,146,255" k="stops"/>
          </colorramp>
          <item label="0" color="#000004" value="0" alpha="255"/>
          <item label="19.6" color="#02020c" value="19.6078" alpha="255"/>
          <item label="39.2" color="#050417" value="39.2157" alpha="255"/>
          <item label="58.8" color="#0a0722" value="58.8235" alpha="255"/>
          <item label="78.4" color="#10092d" value="78.4314" alpha="255"/>
          <item label="98" color="#160b39" value="98.03920000000001" alpha="255"/>
          <item label="118" color="#1e0c45" value="117.647" alpha="255"/>
          <item label="137" color="#260c51" value="137.255" alpha="255"/>
          <item label="157" color="#2f0a5b" value="156.863" alpha="255"/>
          <item label="176" color="#380962" value="176.47099999999998" alpha="255"/>
          <item label="196" color="#400a67" value="196.078" alpha="255"/>
          <item label="216" color="#490b6a" value="215.68599999999998" alpha="255"/>
          <item label="235" color="#510e6c" value="235.294" alpha="255"/>
          <item label="255" color="#59106e" value="254.90200000000002" alpha="255"/>
          <item label="275" color="#61136e" value="274.51" alpha="255"/>
          <item label="294" color="#69166e" value="294.118" alpha="255"/>
          <item label="314" color="#71196e" value="313.72499999999997" alpha="255"/>
          <item label="333" color="#781c6d" value="333.33299999999997" alpha="255"/>
          <item label="353" color="#801f6c" value="352.94100000000003" alpha="255"/>
          <item label="373" color="#88226a" value="372.54900000000004" alpha="255"/>
          <item label="392" color="#902568" value="392.157" alpha="255"/>
          <item label="412" color="#982766" value="411.765" alpha="255"/>
          <item label="431" color="#a02a63" value="431.373" alpha="255"/>
          <item label="451" color="#a82e5f" value="450.98" alpha="255"/>
          <item label="471" color="#b0315b" value="470.588" alpha="255"/>
          <item label="490" color="#b73557" value="490.196" alpha="255"/>
          <item label="510" color="#bf3952" value="509.80400000000003" alpha="255"/>
          <item label="529" color="#c63d4d" value="529.412" alpha="255"/>
          <item label="549" color="#cc4248" value="549.02" alpha="255"/>
          <item label="569" color="#d34743" value="568.627" alpha="255"/>
          <item label="588" color="#d94d3d" value="588.2349999999999" alpha="255"/>
          <item label="608" color="#df5337" value="607.8430000000001" alpha="255"/>
          <item label="627" color="#e45a31" value="627.451" alpha="255"/>
          <item label="647" color="#e9612b" value="647.0590000000001" alpha="255"/>
          <item label="667" color="#ed6925" value="666.667" alpha="255"/>
          <item label="686" color="#f1711f" value="686.275" alpha="255"/>
          <item label="706" color="#f47918" value="705.8820000000001" alpha="255"/>
          <item label="725" color="#f78212" value="725.49" alpha="255"/>
          <item label="745" color="#f98b0b" value="745.0980000000001" alpha="255"/>
          <item label="765" color="#fa9407" value="764.706" alpha="255"/>
          <item label="784" color="#fb9d07" value="784.314" alpha="255"/>
          <item label="804" color="#fca60c" value="803.922" alpha="255"/>
          <item label="824" color="#fcb014" value="823.529" alpha="255"/>
          <item label="843" color="#fbba1f" value="843.1370000000001" alpha="255"/>
          <item label="863" color="#fac42a" value="862.745" alpha="255"/>
          <item label="882" color="#f8cd37" value="882.3530000000001" alpha="255"/>
          <item label="902" color="#f6d746" value="901.961" alpha="255"/>
          <item label="922" color="#f4e156" value="921.569" alpha="255"/>
          <item label="941" color="#f2ea69" value="941.176" alpha="255"/>
          <item label="961" color="#f2f27d" value="960.784" alpha="255"/>
          <item label="980" color="#f5f992" value="980.392" alpha="255"/>
          <item label="1e+03" color="#fcffa4" value="1000" alpha="255"/>
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
