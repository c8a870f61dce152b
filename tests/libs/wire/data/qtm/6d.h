#pragma once
namespace qualisys_cpp_sdk::tests::data
{
    inline const char* Get6DSettingsTest = R"XMLDATA(
<QTM_Parameters_Ver_1.25>
    <The_6D>
        <Body>
            <Name>refined</Name>
            <Enabled>true</Enabled>
            <Color R="0" G="255" B="0"/>
            <MaximumResidual>20.000000</MaximumResidual>
            <MinimumMarkersInBody>3</MinimumMarkersInBody>
            <BoneLengthTolerance>20.000000</BoneLengthTolerance>
            <Filter Preset="No filter"/>
            <Mesh>
                <Name>Arqus.obj</Name>
                <Position X="0.000000" Y="0.000000" Z="0.000000"/>
                <Rotation X="0.000000" Y="0.000000" Z="0.000000"/>
                <Scale>0.010000</Scale>
                <Opacity>1.000000</Opacity>
            </Mesh>
            <Points>
                <Point X="-67.927157" Y="29.810079" Z="-1.592971" Virtual="0" PhysicalId="0" Name="Layout 3 - 1"/>
                <Point X="-95.023059" Y="1.742391" Z="-19.541355" Virtual="0" PhysicalId="0" Name="Layout 3 - 2"/>
                <Point X="-90.017171" Y="19.888814" Z="-57.494654" Virtual="0" PhysicalId="0" Name="Layout 3 - 3"/>
                <Point X="68.316106" Y="29.173523" Z="-1.829020" Virtual="0" PhysicalId="0" Name="Layout 3 - 4"/>
                <Point X="95.027245" Y="1.474449" Z="-19.171870" Virtual="0" PhysicalId="0" Name="Layout 3 - 5"/>
                <Point X="89.624036" Y="20.690744" Z="-57.450130" Virtual="0" PhysicalId="0" Name="Layout 3 - 6"/>
            </Points>
            <Data_origin X="0.000000" Y="0.000000" Z="0.000000" Relative_body="1">0</Data_origin>
            <Data_orientation R11="1.000000" R12="0.000000" R13="0.000000" R21="0.000000" R22="1.000000" R23="0.000000" R31="0.000000" R32="0.000000" R33="1.000000" Relative_body="1">0</Data_orientation>
        </Body>
        <Body>
            <Name>Table</Name>
            <Enabled>true</Enabled>
            <Color R="0" G="0" B="255"/>
            <MaximumResidual>10.000000</MaximumResidual>
            <MinimumMarkersInBody>3</MinimumMarkersInBody>
            <BoneLengthTolerance>10.000000</BoneLengthTolerance>
            <Filter Preset="No filter"/>
            <Mesh>
                <Name/>
                <Position X="0.000000" Y="0.000000" Z="0.000000"/>
                <Rotation X="0.000000" Y="0.000000" Z="0.000000"/>
                <Scale>1.000000</Scale>
                <Opacity>1.000000</Opacity>
            </Mesh>
            <Points>
                <Point X="801.422010" Y="368.889193" Z="2.142416" Virtual="0" PhysicalId="0" Name="Table - 1"/>
                <Point X="777.315122" Y="-413.341275" Z="4.127203" Virtual="0" PhysicalId="0" Name="Table - 2"/>
                <Point X="-778.145542" Y="412.610612" Z="-2.278264" Virtual="0" PhysicalId="0" Name="Table - 3"/>
                <Point X="-800.591590" Y="-368.158531" Z="-3.991355" Virtual="0" PhysicalId="0" Name="Table - 4"/>
            </Points>
            <Data_origin X="0.000000" Y="0.000000" Z="0.000000" Relative_body="1">0</Data_origin>
            <Data_orientation R11="1.000000" R12="0.000000" R13="0.000000" R21="0.000000" R22="1.000000" R23="0.000000" R31="0.000000" R32="0.000000" R33="1.000000" Relative_body="1">0</Data_orientation>
        </Body>
        <Body>
            <Name>Screen2</Name>
            <Enabled>true</Enabled>
            <Color R="255" G="0" B="255"/>
            <MaximumResidual>10.000000</MaximumResidual>
            <MinimumMarkersInBody>3</MinimumMarkersInBody>
            <BoneLengthTolerance>10.000000</BoneLengthTolerance>
            <Filter Preset="No filter"/>
            <Mesh>
                <Name/>
                <Position X="0.000000" Y="0.000000" Z="0.000000"/>
                <Rotation X="0.000000" Y="0.000000" Z="0.000000"/>
                <Scale>1.000000</Scale>
                <Opacity>1.000000</Opacity>
            </Mesh>
            <Points>
                <Point X="177.895605" Y="-40.203524" Z="-276.061206" Virtual="0" PhysicalId="0" Name="Screen2 - 1"/>
                <Point X="-176.929252" Y="41.059151" Z="276.110102" Virtual="0" PhysicalId="0" Name="Screen2 - 2"/>
                <Point X="-111.494821" Y="129.602182" Z="-283.761580" Virtual="0" PhysicalId="0" Name="Screen2 - 3"/>
                <Point X="110.528467" Y="-130.457810" Z="283.712683" Virtual="0" PhysicalId="0" Name="Screen2 - 4"/>
            </Points>
            <Data_origin X="0.000000" Y="0.000000" Z="0.000000" Relative_body="1">0</Data_origin>
            <Data_orientation R11="1.000000" R12="0.000000" R13="0.000000" R21="0.000000" R22="1.000000" R23="0.000000" R31="0.000000" R32="0.000000" R33="1.000000" Relative_body="1">0</Data_orientation>
        </Body>
        <Body>
            <Name>Cup</Name>
            <Enabled>true</Enabled>
            <Color R="255" G="255" B="0"/>
            <MaximumResidual>10.000000</MaximumResidual>
            <MinimumMarkersInBody>3</MinimumMarkersInBody>
            <BoneLengthTolerance>10.000000</BoneLengthTolerance>
            <Filter Preset="No filter"/>
            <Mesh>
                <Name/>
                <Position X="0.000000" Y="0.000000" Z="0.000000"/>
                <Rotation X="0.000000" Y="0.000000" Z="0.000000"/>
                <Scale>1.000000</Scale>
                <Opacity>1.000000</Opacity>
            </Mesh>
            <Points>
                <Point X="-16.409485" Y="43.238453" Z="-7.375008" Virtual="0" PhysicalId="0" Name="Cup - 1"/>
                <Point X="41.237583" Y="9.395873" Z="-14.994871" Virtual="0" PhysicalId="0" Name="Cup - 2"/>
                <Point X="-6.343689" Y="-32.749109" Z="-24.391156" Virtual="0" PhysicalId="0" Name="Cup - 3"/>
                <Point X="27.211503" Y="-35.510982" Z="31.208097" Virtual="0" PhysicalId="0" Name="Cup - 4"/>
                <Point X="-45.695912" Y="15.625764" Z="15.552938" Virtual="0" PhysicalId="0" Name="Cup - 5"/>
            </Points>
            <Data_origin X="0.000000" Y="0.000000" Z="0.000000" Relative_body="1">0</Data_origin>
            <Data_orientation R11="1.000000" R12="0.000000" R13="0.000000" R21="0.000000" R22="1.000000" R23="0.000000" R31="0.000000" R32="0.000000" R33="1.000000" Relative_body="1">0</Data_orientation>
        </Body>
        <Body>
            <Name>Phone</Name>
            <Enabled>true</Enabled>
            <Color R="0" G="255" B="255"/>
            <MaximumResidual>10.000000</MaximumResidual>
            <MinimumMarkersInBody>3</MinimumMarkersInBody>
            <BoneLengthTolerance>10.000000</BoneLengthTolerance>
            <Filter Preset="No filter"/>
            <Mesh>
                <Name/>
                <Position X="0.000000" Y="0.000000" Z="0.000000"/>
                <Rotation X="0.000000" Y="0.000000" Z="0.000000"/>
                <Scale>1.000000</Scale>
                <Opacity>1.000000</Opacity>
            </Mesh>
            <Points>
                <Point X="-39.974045" Y="-68.138270" Z="-0.101279" Virtual="0" PhysicalId="0" Name="Phone - 1"/>
                <Point X="43.348296" Y="64.030668" Z="-2.407927" Virtual="0" PhysicalId="0" Name="Phone - 2"/>
                <Point X="-31.906718" Y="75.069956" Z="1.213906" Virtual="0" PhysicalId="0" Name="Phone - 3"/>
                <Point X="28.532467" Y="-70.962354" Z="1.295299" Virtual="0" PhysicalId="0" Name="Phone - 4"/>
            </Points>
            <Data_origin X="0.000000" Y="0.000000" Z="0.000000" Relative_body="1">0</Data_origin>
            <Data_orientation R11="1.000000" R12="0.000000" R13="0.000000" R21="0.000000" R22="1.000000" R23="0.000000" R31="0.000000" R32="0.000000" R33="1.000000" Relative_body="1">0</Data_orientation>
        </Body>
        <Body>
            <Name>Screen1</Name>
            <Enabled>true</Enabled>
            <Color R="127" G="0" B="0"/>
            <MaximumResidual>10.000000</MaximumResidual>
            <MinimumMarkersInBody>3</MinimumMarkersInBody>
            <BoneLengthTolerance>10.000000</BoneLengthTolerance>
            <Filter Preset="No filter"/>
            <Mesh>
                <Name/>
                <Position X="0.000000" Y="0.000000" Z="0.000000"/>
                <Rotation X="0.000000" Y="0.000000" Z="0.000000"/>
                <Scale>1.000000</Scale>
                <Opacity>1.000000</Opacity>
            </Mesh>
            <Points>
                <Point X="-395.500599" Y="5.139634" Z="-195.481255" Virtual="0" PhysicalId="0" Name="Screen - 1"/>
                <Point X="392.106423" Y="-2.138403" Z="196.007090" Virtual="0" PhysicalId="0" Name="Screen - 2"/>
                <Point X="402.905766" Y="26.186535" Z="-178.268136" Virtual="0" PhysicalId="0" Name="Screen - 3"/>
                <Point X="-399.511589" Y="-29.187767" Z="177.742302" Virtual="0" PhysicalId="0" Name="Screen - 4"/>
            </Points>
            <Data_origin X="0.000000" Y="0.000000" Z="0.000000" Relative_body="1">0</Data_origin>
            <Data_orientation R11="1.000000" R12="0.000000" R13="0.000000" R21="0.000000" R22="1.000000" R23="0.000000" R31="0.000000" R32="0.000000" R33="1.000000" Relative_body="1">0</Data_orientation>
        </Body>
    </The_6D>
</QTM_Parameters_Ver_1.25>
)XMLDATA";

    inline const char* Set6DSettingsTest = R"XMLDATA(
<QTM_Settings>
    <The_6D>
        <Body>
            <Name>test</Name>
            <Enabled>true</Enabled>
            <Color R="123" G="0" B="0"/>
            <MaximumResidual>999.000000</MaximumResidual>
            <MinimumMarkersInBody>321</MinimumMarkersInBody>
            <BoneLengthTolerance>888.000000</BoneLengthTolerance>
            <Filter Preset="false"/>
            <Mesh>
                <Name>test2</Name>
                <Position X="1.000000" Y="2.000000" Z="3.000000"/>
                <Rotation X="4.000000" Y="5.000000" Z="6.000000"/>
                <Scale>22.000000</Scale>
                <Opacity>11.000000</Opacity>
            </Mesh>
            <Points>
                <Point X="41.000000" Y="42.000000" Z="43.000000" Virtual="0" PhysicalId="65" Name="bodyName"/>
            </Points>
            <Data_origin X="7.000000" Y="8.000000" Z="9.000000" Relative_body="7">0</Data_origin>
            <Data_orientation R11="0.100000" R12="0.200000" R13="0.300000" R21="0.400000" R22="0.500000" R23="0.600000" R31="0.700000" R32="0.800000" R33="0.900000" Relative_body="7">0</Data_orientation>
        </Body>
    </The_6D>
</QTM_Settings>
)XMLDATA";
}