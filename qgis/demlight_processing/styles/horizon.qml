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
    <rasterrenderer alphaBand="-1" opacity="1" classificationMax="30" band="1" nodataColor="" type="singlebandpseudocolor" classificationMin="0">
      <minMaxOrigin>
        <limits>None</limits>
        <extent>WholeRaster</extent>
        <statAccuracy>Estimated</statAccuracy>
        <cumulativeCutLower>0.02</cumulativeCutLower>
        <cumulativeCutUpper>0.98</cumulativeCutUpper>
        <stdDevFactor>2</stdDevFactor>
      </minMaxOrigin>
      <rastershader>
        <colorrampshader clip="0" minimumValue="0" maximumValue="30" classificationMode="1" labelPrecision="6" colorRampType="INTERPOLATED">
          <colorramp name="[source]" type="gradient">
            <Option type="Map">
              <Option name="color1" type="QString" value="68,1,84,255"/>
              <Option name="color2" type="QString" value="253,231,37,255"/>
              <Option name="discrete" type="QString" value="0"/>
              <Option name="rampType" type="QString" value="gradient"/>
              <Option name="stops" type="QString" value="0.0196078;70,8,92,255:0.0392157;71,16,99,255:0.0588235;72,23,105,255:0.0784314;72,29,111,255:0.0980392;72,36,117,255:0.117647;71,42,122,255:0.137255;70,48,126,255:0.156863;69,55,129,255:0.176471;67,61,132,255:0.196078;65,66,135,255:0.215686;63,72,137,255:0.235294;61,78,138,255:0.254902;58,83,139,255:0.27451;56,89,140,255:0.294118;53,94,141,255:0.313725;51,99,141,255:0.333333;49,104,142,255:0.352941;46,109,142,255:0.372549;44,113,142,255:0.392157;42,118,142,255:0.411765;41,123,142,255:0.431373;39,128,142,255:0.45098;37,132,142,255:0.470588;35,137,142,255:0.490196;33,142,141,255:0.509804;32,146,140,255:0.529412;31,151,139,255:0.54902;30,156,137,255:0.568627;31,161,136,255:0.588235;33,165,133,255:0.607843;36,170,131,255:0.627451;40,174,128,255:0.647059;46,179,124,255:0.666667;53,183,121,255:0.686275;61,188,116,255:0.705882;70,192,111,255:0.72549;80,196,106,255:0.745098;90,200,100,255:0.764706;101,203,94,255:0.784314;112,207,87,255:0.803922;124,210,80,255:0.823529;137,213,72,255:0.843137;149,216,64,255:0.862745;162,218,55,255:0.882353;176,221,47,255:0.901961;189,223,38,255:0.921569;202,225,31,255:0.941176;216,226,25,255:0.960784;229,228,25,255:0.980392;241,229,29,255"/>
            </Option>
            <prop v="68,1,84,255" k="color1"/>
            <prop v="253,231,37,255" k="color2"/>
            <prop v="0" k="discrete"/>
            <prop v="gradient" k="rampType"/>
            <prop v="0.0196078;70,8,92,255:0.0392157;71,16,99,255:0.0588235;72,23,105,255:0.0784314;72,29,111,255:0.0980392;72,36,117,255:0.117647;71,42,122,255:0.137255;70,48,126,255:0.156863;69,55,129,255:0.176471;67,61,132,255:0.196078;65,66,135,255:0.215686;63,72,137,255:0.235294;61,78,138,255:0.254902;58,83,139,255:0.27451;56,89,140,255:0.294118;53,94,141,255:0.313725;51,99,141,255:0.333333;49,104,142,255:0.352941;46,109,142,255:0.372549;44,113,142,255:0.392157;42,118,142,255:0.411765;41,123,142,255:0.431373;39,128,142,255:0.45098;37,132,142,255:0.470588;35,137,142,255:0.490196;33,142,141,255:0.509804;32,146,140,255:0.529412;31,151,139,255:0.54902;30,156,137,255:0.568627;31,161,136,255:0.588235;33,165,133,255:0.607843;36,170,131,255:0.627451;40,174,128,255:0.647059;46,179,124,255:0.666667;53,183,121,255:0.686275;61,188,116,255:0.705882;70,192,111,255:0.72549;80,196,106,255:0.745098;90,200,100,255:0.764706;101,203,94,255:0.784314;112,207,87,255:0.803922;124,210,80,255:0.823529;137,213,72,255:0.843137;149,216,64,255:0.862745;162,218,55,255:0.882353;176,221,47,255:0.901961;189,223,38,255:0.921569;202,225,31,255:0.941176;216,226,25,255:0.960784;229,228,25,255:0.980392;241,229,29,255" k="stops"/>
          </colorramp>
          <item label="0" color="#440154" value="0" alpha="255"/>
          <item label="0.588" color="#46085c" value="0.588234" alpha="255"/>
          <item label="1.18" color="#471063" value="1.176471" alpha="255"/>
          <item label="1.76" color="#481769" value="1.764705" alpha="255"/>
          <item label="2.35" color="#481d6f" value="2.352942" alpha="255"/>
          <item label="2.94" color="#482475" value="2.941176" alpha="255"/>
          <item label="3.53" color="#472a7a" value="3.52941" alpha="255"/>
          <item label="4.12" color="#46307e" value="4.11765" alpha="255"/>
          <item label="4.71" color="#453781" value="4.70589" alpha="255"/>
          <item label="5.29" color="#433d84" value="5.29413" alpha="255"/>
          <item label="5.88" color="#414287" value="5.88234" alpha="255"/>
          <item label="6.47" color="#3f4889" value="6.47058" alpha="255"/>
          <item label="7.06" color="#3d4e8a" value="7.05882" alpha="255"/>
          <item label="7.65" color="#3a538b" value="7.647060000000001" alpha="255"/>
          <item label="8.24" color="#38598c" value="8.235299999999999" alpha="255"/>
          <item label="8.82" color="#355e8d" value="8.82354" alpha="255"/>
          <item label="9.41" color="#33638d" value="9.41175" alpha="255"/>
          <item label="10" color="#31688e" value="9.99999" alpha="255"/>
          <item label="10.6" color="#2e6d8e" value="10.58823" alpha="255"/>
          <item label="11.2" color="#2c718e" value="11.17647" alpha="255"/>
          <item label="11.8" color="#2a768e" value="11.76471" alpha="255"/>
          <item label="12.4" color="#297b8e" value="12.35295" alpha="255"/>
          <item label="12.9" color="#27808e" value="12.94119" alpha="255"/>
          <item label="13.5" color="#25848e" value="13.529399999999999" alpha="255"/>
          <item label="14.1" color="#23898e" value="14.11764" alpha="255"/>
          <item label="14.7" color="#218e8d" value="14.70588" alpha="255"/>
          <item label="15.3" color="#20928c" value="15.294120000000001" alpha="255"/>
          <item label="15.9" color="#1f978b" value="15.88236" alpha="255"/>
          <item label="16.5" color="#1e9c89" value="16.470599999999997" alpha="255"/>
          <item label="17.1" color="#1fa188" value="17.05881" alpha="255"/>
          <item label="17.6" color="#21a585" value="17.64705" alpha="255"/>
          <item label="18.2" color="#24aa83" value="18.23529" alpha="255"/>
          <item label="18.8" color="#28ae80" value="18.823529999999998" alpha="255"/>
          <item label="19.4" color="#2eb37c" value="19.41177" alpha="255"/>
          <item label="20" color="#35b779" value="20.00001" alpha="255"/>
          <item label="20.6" color="#3dbc74" value="20.58825" alpha="255"/>
          <item label="21.2" color="#46c06f" value="21.17646" alpha="255"/>
          <item label="21.8" color="#50c46a" value="21.764699999999998" alpha="255"/>
          <item label="22.4" color="#5ac864" value="22.35294" alpha="255"/>
          <item label="22.9" color="#65cb5e" value="22.94118" alpha="255"/>
          <item label="23.5" color="#70cf57" value="23.52942" alpha="255"/>
          <item label="24.1" color="#7cd250" value="24.11766" alpha="255"/>
          <item label="24.7" color="#89d548" value="24.705869999999997" alpha="255"/>
          <item label="25.3" color="#95d840" value="25.29411" alpha="255"/>
          <item label="25.9" color="#a2da37" value="25.88235" alpha="255"/>
          <item label="26.5" color="#b0dd2f" value="26.47059" alpha="255"/>
          <item label="27.1" color="#bddf26" value="27.05883" alpha="255"/>
          <item label="27.6" color="#cae11f" value="27.64707" alpha="255"/>
          <item label="28.2" color="#d8e219" value="28.23528" alpha="255"/>
          <item label="28.8" color="#e5e419" value="28.82352" alpha="255"/>
          <item label="29.4" color="#f1e51d" value="29.41176" alpha="255"/>
          <item label="30" color="#fde725" value="30" alpha="255"/>
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
